import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, throwsCode } from './load.mjs';

// The ColorChecker through the virtual camera as in Shen et al. 2008 eq (29): 8-bit, γ = 1.8, l = 22.
async function simulatedCC24() {
  const T = await loadTristim();
  const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D65',
    { whiteLevel: 80, oecfGamma: 1.8, oecfScale: 22, clipMax: 255, quantise: 1 });
  return { T, rgb: sim.RGB, ids: sim.ids };
}

test('listLinearisations describes the table with option schemas', async () => {
  const T = await loadTristim();
  const rows = T.listLinearisations();
  assert.deepEqual(rows.map((r) => r.id), ['identity', 'gamma', 'sRGB', 'grey-polynomial', 'grey-log-polynomial',
    'colour-polynomial', 'colour-log-polynomial', 'Shen2008']);
  const shen = rows.find((r) => r.id === 'Shen2008');
  assert.equal(shen.needs, 'reflectances');
  const byName = Object.fromEntries(shen.options.map((o) => [o.name, o]));
  assert.equal(byName.J.default, 8);
  assert.equal(byName.K.default, 2);
  assert.equal(byName.L.default, 2);
  assert.deepEqual(byName.basis.choices, ['munsell1269', 'patches', 'user']);
});

test('fitLinearisation: Shen2008 on non-grey ColorChecker patches, R² against the greys, curves', async () => {
  const { T, rgb, ids } = await simulatedCC24();
  const r = T.fitLinearisation({ method: 'Shen2008', parameters: { J: 8 }, settings: { grey: 'D1;D2;D3;D4;D5;D6' } },
    { rgb, ids, reflectances: 'cc24', fullScale: 255 });
  assert.equal(r.linear.length, 72);
  assert.deepEqual(r.greys, ['D1', 'D2', 'D3', 'D4', 'D5', 'D6']);
  assert.equal(r.fitted.length, 18);
  for (const v of r.rSquared) assert.ok(v > 0.995, `R² ${v}`);
  assert.equal(r.curves.length, 3);
  assert.equal(r.curves[1].greyBased.length, 101);
  assert.ok(Math.abs(r.curves[0].linear[100] - 1) < 1e-12);
  // the fitted JSON applies again to the same values
  const again = T.applyLinearisation(r.linearisation, rgb);
  assert.deepEqual(Array.from(again), Array.from(r.linear));
});

test('fitSpectral: estimates, spectral RMS and CIEDE2000 per patch', async () => {
  const { T, rgb, ids } = await simulatedCC24();
  const lin = T.fitLinearisation('Shen2008', { rgb, ids, reflectances: 'cc24', fullScale: 255 });
  const s = T.fitSpectral(lin.linearisation, { rgb, ids, reflectances: 'cc24' }, 'D65', '1931');
  assert.equal(s.rms.length, 24);
  assert.equal(s.estimates.length, 24 * s.wavelengths.length);
  assert.ok(s.summary.rmsMean > 0 && s.summary.rmsMean < 0.08, `rms ${s.summary.rmsMean}`);
  assert.equal(s.model.format, 'tristim-spectral');
});

test('linearisation bad input: coded errors', async () => {
  const { T, rgb, ids } = await simulatedCC24();
  throwsCode(assert, () => T.fitLinearisation('Shen2008:J=17,grey=D1;D2;D3;D4;D5;D6',
    { rgb, ids, reflectances: 'cc24', fullScale: 255 }), 'TOO_FEW_PATCHES');
  throwsCode(assert, () => T.fitLinearisation('Shen2008', { rgb, ids }), 'MISSING_COLUMN');
  throwsCode(assert, () => T.fitLinearisation('spline', { rgb, ids }), 'UNKNOWN_ID');
  throwsCode(assert, () => T.fitLinearisation('gamma', { rgb: [1, 2], ids: [] }), 'ROW_LENGTH');
  const narrow = { wavelengths: [450, 500, 550, 600, 650], ids, spectra: new Float64Array(24 * 5).fill(0.5) };
  throwsCode(assert, () => T.fitLinearisation('Shen2008', { rgb, ids, reflectances: narrow, fullScale: 255 }),
    'WAVELENGTH_MISMATCH');
});

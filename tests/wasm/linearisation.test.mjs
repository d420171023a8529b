import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, throwsCode } from './load.mjs';

// The ColorChecker through the virtual camera as in Shen et al. 2008 eq (29): 8-bit, γ = 1.8, l = 22.
async function simulatedCC24() {
  const T = await loadTristim();
  const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D65',
    { white_level: 80, oecf: true, oecf_gamma: 1.8, oecf_scale: 22, clip_max: 255, quantise: true });
  return { T, rgb: sim.RGB, ids: sim.ids, cc24: T.chartReflectances('cc24') };
}

test('listLinearisations describes the table with option schemas', async () => {
  const T = await loadTristim();
  const rows = T.listLinearisations();
  assert.deepEqual(rows.map((r) => r.id), ['identity', 'gamma', 'sRGB', 'grey-polynomial', 'grey-log-polynomial',
    'colour-polynomial', 'colour-log-polynomial', 'Guarnera2018', 'Shen2008']);
  assert.equal(rows.find((r) => r.id === 'Guarnera2018').needs, 'reference');
  const shen = rows.find((r) => r.id === 'Shen2008');
  assert.equal(shen.needs, 'reflectances');
  const byName = Object.fromEntries(shen.options.map((o) => [o.name, o]));
  assert.equal(byName.J.default_number, 8);
  assert.equal(byName.K.default_number, 2);
  assert.equal(byName.L.default_number, 2);
  assert.deepEqual(byName.basis.choices, ['munsell1269', 'patches', 'user']);
});

test('fitLinearisation: Shen2008 on non-grey ColorChecker patches, R² against the greys, curves', async () => {
  const { T, rgb, ids, cc24 } = await simulatedCC24();
  const data = { camera_RGB: rgb, ids, reflectances: cc24, full_scale: 255 };
  const r = T.fitLinearisation({ method: 'Shen2008', parameters: { J: 8 }, settings: { grey: 'D1;D2;D3;D4;D5;D6' } }, data);
  const linear = T.linearise(r, rgb);
  assert.equal(linear.length, 72);
  assert.deepEqual(r.greys, ['D1', 'D2', 'D3', 'D4', 'D5', 'D6']);
  assert.equal(r.fitted.length, 18);
  for (const v of r.r_squared) assert.ok(v > 0.995, `R² ${v}`);
  const curves = [0, 1, 2].map((c) => T.sampleCurve(r, c, 101));
  assert.equal(curves[1].grey_based.length, 101);
  assert.ok(Math.abs(curves[0].linear[100] - 1) < 1e-12);
  // the fitted curve crosses back as a plain object and through its JSON, and applies the same
  assert.deepEqual(Array.from(T.linearise(T.linearisationFromJson(T.linearisationToJson(r)), rgb)), Array.from(linear));
  // the inverse gives the stored values back over the fitted range
  const back = T.delinearise(r, linear);
  for (let i = 0; i < 72; i++) assert.ok(Math.abs(back[i] - rgb[i]) < 1e-6 * 255 + 1e-9 || rgb[i] >= 254, `${i}: ${back[i]} vs ${rgb[i]}`);
});

test('fitSpectral: estimates, spectral RMS and CIEDE2000 per patch', async () => {
  const { T, rgb, ids, cc24 } = await simulatedCC24();
  const lin = T.fitLinearisation('Shen2008', { camera_RGB: rgb, ids, reflectances: cc24, full_scale: 255 });
  const model = T.fitSpectral(lin, ids, rgb, cc24);
  // the paper's training set: the non-grey patches (the automatic rule finds D2-D6 grey)
  assert.equal(model.training_set, 'non-grey');
  assert.deepEqual(model.greys, ['D2', 'D3', 'D4', 'D5', 'D6']);
  assert.equal(model.training_patches, 19);
  assert.equal(T.fitSpectral(lin, ids, rgb, cc24, { method: '', parameters: { use_greys: 1 }, settings: {} }).training_patches, 24);
  assert.deepEqual(T.spectralMethod().options.map((o) => o.name), ['grey', 'grey_threshold', 'use_greys']);
  assert.equal(model.W.length, model.wavelengths.length);  // W: a row [w_R, w_G, w_B] per wavelength
  assert.ok(model.W.every((row) => row.length === 3));
  const est = T.estimateReflectances(model, ids, rgb);
  assert.equal(est.values.length, 24);
  assert.equal(est.values[0].length, model.wavelengths.length);
  const e = T.evaluateSpectral(model, ids, rgb, cc24, 'D65', '1931');
  assert.equal(e.patches.length, 24);
  assert.ok(e.summary.spectral_rms_mean > 0 && e.summary.spectral_rms_mean < 0.08, `rms ${e.summary.spectral_rms_mean}`);
  assert.match(T.spectralModelToJson(model), /"format": "tristim-spectral"/);
  assert.match(T.spectralCsv(est), /^wavelength_nm,A1,/);
});

test('linearisation bad input: coded errors', async () => {
  const { T, rgb, ids, cc24 } = await simulatedCC24();
  throwsCode(assert, () => T.fitLinearisation('Shen2008:J=17,grey=D1;D2;D3;D4;D5;D6',
    { camera_RGB: rgb, ids, reflectances: cc24, full_scale: 255 }), 'TOO_FEW_PATCHES');
  throwsCode(assert, () => T.fitLinearisation('Shen2008', { camera_RGB: rgb, ids }), 'MISSING_COLUMN');
  throwsCode(assert, () => T.fitLinearisation('spline', { camera_RGB: rgb, ids }), 'UNKNOWN_ID');
  throwsCode(assert, () => T.fitLinearisation('gamma', { camera_RGB: [1, 2], ids: [] }), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.fitLinearisation('gamma', { camera_RGB: rgb, ids, fullscale: 255 }), 'INVALID_ARGUMENT');
  const narrow = { wavelengths: [450, 500, 550, 600, 650], names: ids, values: ids.map(() => [0.5, 0.5, 0.5, 0.5, 0.5]) };
  throwsCode(assert, () => T.fitLinearisation('Shen2008', { camera_RGB: rgb, ids, reflectances: narrow, full_scale: 255 }),
    'WAVELENGTH_MISMATCH');
});

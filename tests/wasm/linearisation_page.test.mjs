// The linearisation step's worker handler (web/linearisation/handlers.js) on the engine in node:
// the R² it computes for rows the engine does not compare with the greys follows the engine's
// definition for Shen2008 (same greys, same order K, same samples: the same number), and on the
// paper's simulated scanner (eq 29: γ = 1.8, l = 22, 8 bit) the handler returns the curves, the
// grey comparison and the spectral characterisation for the page.
import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim } from './load.mjs';
import { handlers, compareWithGreys, squaredCorrelation } from '../../web/linearisation/handlers.js';

async function scanner() {
  const T = await loadTristim();
  const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D65',
    { white_level: 80, oecf: true, oecf_gamma: 1.8, oecf_scale: 22, clip_max: 255, quantise: true });
  const ref = T.referenceChart('cc24', 'D65', '1931');
  return { T, ids: sim.ids, rgb: sim.RGB, xyz: ref.XYZ, white: Array.from(ref.white) };
}

test('the page\'s grey comparison is the engine\'s R² for Shen2008', async () => {
  const { T, ids, rgb, xyz, white } = await scanner();
  const data = { ids, camera_RGB: rgb, reference_XYZ: xyz, white, reflectances: T.chartReflectances('cc24'), full_scale: 255 };
  for (const K of [1, 2, 3]) {
    const lin = T.fitLinearisation({ method: 'Shen2008', parameters: { K } }, data);
    const mine = compareWithGreys(T, lin, data, { generic: true });
    assert.deepEqual(mine.greys, lin.greys);
    mine.r_squared.forEach((v, c) => assert.ok(Math.abs(v - lin.r_squared[c]) < 1e-9,
      `K ${K} channel ${'RGB'[c]}: page ${v}, engine ${lin.r_squared[c]}`));
  }
  assert.equal(squaredCorrelation([1, 2, 3], [2, 4, 6]), 1);
  assert.ok(Number.isNaN(squaredCorrelation([1, 1, 1], [1, 2, 3])));
});

test('linearisationFit: gamma and Shen2008 on the simulated scanner, with the spectral characterisation', async () => {
  const { T, ids, rgb, xyz, white } = await scanner();
  const args = { ids, rgb, xyz, white, chart: 'cc24', surface: { method: 'none' }, fullScale: 255, illuminant: 'D65', observer: '1931' };
  const progress = () => {};
  const g = handlers.linearisationFit(T, { ...args, choice: { method: 'gamma', parameters: { gamma: 1.8 } } }, { progress }).result;
  assert.equal(g.comparison.source, 'page');
  assert.ok(g.comparison.greys.length >= 5 && g.comparison.greys.every((id) => /^D[1-6]$/.test(id)), `greys ${g.comparison.greys}`);
  for (const v of g.comparison.r_squared) assert.ok(v > 0.999, `gamma 1.8 R² ${g.comparison.r_squared}`);
  // a wrong exponent agrees less with the greys
  const wrong = handlers.linearisationFit(T, { ...args, choice: { method: 'gamma', parameters: { gamma: 1 } } }, { progress }).result;
  wrong.comparison.r_squared.forEach((v, c) => assert.ok(v < g.comparison.r_squared[c], `γ 1: ${v}, γ 1.8: ${g.comparison.r_squared[c]}`));
  for (const s of g.comparison.curves) assert.ok(Math.abs(s.grey_based.at(-1) - 1) < 1e-12);
  const s = handlers.linearisationFit(T, { ...args, choice: { method: 'Shen2008', parameters: {}, settings: {} } }, { progress }).result;
  assert.equal(s.comparison.source, 'engine');
  assert.deepEqual(s.comparison.r_squared, Array.from(s.lin.r_squared));
  assert.equal(s.linear.length, 72);
  assert.equal(s.spectral.ids.length, 24);
  assert.equal(s.spectral.estimated.length, 24);
  assert.equal(s.spectral.measured.values[0].length, s.spectral.measured.wavelengths.length);
  assert.ok(s.spectral.summary.spectral_rms_mean > 0 && s.spectral.summary.spectral_rms_mean < 0.08, `spectral RMS ${s.spectral.summary.spectral_rms_mean}`);
});

// The page's pairing (web/lib/pairs.js through the worker handler pairSample, web/fit/handlers.js)
// is the engine's: on a planted sample (the virtual camera's cc24, patches in reverse order, one
// saturated, one dark, one outside the frame) it keeps the sample's order, leaves out what the
// recipe's sampling stage says, hands the values through untouched, and pairs as the fit does
// (fitSample's training ids and camera RGB: the order `tristim fit --recipe` trains in).
import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim } from './load.mjs';
import { handlers } from '../../web/fit/handlers.js';
import { pairData, excludedBy } from '../../web/lib/pairs.js';

test('pairData is the engine\'s trainingSet: order, exclusions, values, coded refusals', async () => {
  const T = await loadTristim();
  const engine = { call: async (name, payload) => handlers[name](T, payload, {}).result };
  const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D65', {});
  const ref = { ...T.referenceChart('cc24', 'D65', '1931'), settings: { chart: 'cc24' }, source: 'built-in', data_digest: '' };
  const flagsOf = { A2: ['saturated'], B1: ['dark'] };
  const order = sim.ids.map((id, i) => i).reverse().filter((i) => sim.ids[i] !== 'D6');
  const patches = order.map((i) => ({ id: sim.ids[i], mean: Array.from(sim.RGB.subarray(3 * i, 3 * i + 3)), flags: flagsOf[sim.ids[i]] ?? [] }));
  const sample = { patches, missing: ['D6'], ids: patches.map((p) => p.id), flags: patches.map((p) => p.flags) };
  const saturated = excludedBy(sample, (f) => f.includes('saturated'));
  assert.deepEqual(saturated, ['A2']);

  const d = await pairData(engine, sample, ref, { exclude: saturated, exclude_flagged: false });
  const kept = order.filter((i) => sim.ids[i] !== 'A2');
  assert.deepEqual(d.ids, kept.map((i) => sim.ids[i]));   // the sample's order, not the reference's
  assert.deepEqual(d.excluded, ['A2 (excluded)', 'D6 (outside the frame)']);
  kept.forEach((i, r) => {
    for (let c = 0; c < 3; c++) {
      assert.equal(d.rgb[3 * r + c], sim.RGB[3 * i + c]);
      assert.equal(d.xyz[3 * r + c], ref.XYZ[3 * i + c]);
    }
  });
  const all = await pairData(engine, sample, ref, { exclude: [], exclude_flagged: true });
  assert.deepEqual(all.excluded, ['B1 (dark)', 'A2 (saturated)', 'D6 (outside the frame)']);

  // The fit trains on the same rows in the same order.
  const { source, settings, data_digest, ...reference } = ref;
  const recipe = { reference: { chart: 'cc24', illuminant: 'D65', observer: '1931' }, sampling: { exclude: saturated, exclude_flagged: false },
    characterisation: { model: 'matrix-3x3', lab_white: Array.from(ref.white) } };
  const fit = T.fitSample(recipe, { patches, missing: ['D6'] }, reference);
  assert.deepEqual(fit.ids, d.ids);
  assert.deepEqual(Array.from(fit.linear_RGB), Array.from(d.rgb));

  await assert.rejects(pairData(engine, { patches: [{ id: 'Z9', mean: [1, 2, 3] }] }, ref), { code: 'PATCH_MISMATCH' });
  await assert.rejects(pairData(engine, { patches: patches.slice(0, 1) }, ref, { exclude: [patches[0].id] }), { code: 'TOO_FEW_PATCHES' });
});

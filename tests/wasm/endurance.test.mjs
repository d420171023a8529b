// Leaks: 100 consecutive decodes + samplings + fits in one module, as the page's worker does them
// (decodeRaw, sampleChart, fitSample with the example recipe, the handle deleted afterwards), plus
// a refused bad input each time. The module's memory (wasm memory grows to its peak and never
// shrinks) must not grow after the first round by more than 1 MB: a leak of the decoded image
// (~6 MB) or of the sample would grow it by hundreds of MB.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { loadTristim, readBytes, repoRoot, testFiles } from './load.mjs';

test('100 decodes, samplings and fits in one module leave its memory where the first left it (±1 MB)', async () => {
  const T = await loadTristim();
  const dng = readBytes(testFiles.passportDng);
  const recipe = fs.readFileSync(path.join(repoRoot, 'examples/recipes/passport-rootpoly2-psm.json'), 'utf8');
  const r = JSON.parse(recipe);
  const reference = T.referenceChart(r.reference.chart, r.reference.illuminant, r.reference.observer);
  const truncated = dng.slice(0, 1 << 20);
  const round = () => {
    const raw = T.decodeRaw(dng);
    try {
      const s = T.sampleChart(raw, { chart: 'passport' }, r.sampling.corners, { area: r.sampling.area });
      const out = T.fitSample(recipe, { layout: s.layout, homography: s.homography, patches: s.patches }, reference);
      assert.ok(out.profile.length > 100);
    } finally {
      raw.delete();
    }
    assert.throws(() => T.decodeRaw(truncated), (e) => e.code === 'RAW_TRUNCATED');
  };
  round();
  round();
  const start = T.HEAP8.buffer.byteLength;
  const t0 = Date.now();
  for (let i = 0; i < 100; i++) round();
  const end = T.HEAP8.buffer.byteLength;
  console.log(`100 rounds in ${((Date.now() - t0) / 1000).toFixed(1)} s; wasm memory ${(start / 2 ** 20).toFixed(1)} MB -> ${(end / 2 ** 20).toFixed(1)} MB`);
  assert.ok(end - start <= 1 << 20, `wasm memory grew by ${((end - start) / 2 ** 20).toFixed(1)} MB`);
});

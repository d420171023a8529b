// Journey: a grid the Lab renders (Munsell chips, noise off) opened in the journey (issue 45). The
// Images step takes the render's layout (custom rows × columns, no gap) and corners with no
// detection and no hand work, step 1 takes the render's XYZ of each cell as the reference, the
// sampled camera RGB equal the truth's, and a fit runs. 7 chips leave R2C4 of the 2 × 4 grid
// empty: the truth has it as a board patch, so it is sampled, in the reference, and fitted.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { pageTest, step, fitMatrix3x3, waitSampled } from './journey.mjs';

const S = '#step-lab';

pageTest('lab render: a Munsell grid with an empty cell opened in the journey is sampled with the render\'s layout and corners, and fitted', async ({ page }) => {
  await step(page, 'lab');
  await page.selectOption(`${S} select >> nth=0`, 'Nikon_D850');
  await page.selectOption(`${S} select >> nth=2`, 'D50');
  await page.fill(`${S} input[data-lab="shot_gain"]`, '0');
  await page.fill(`${S} input[data-lab="read_noise"]`, '0');
  await page.focus(`${S} select[data-lab="munsell-chips"]`);
  await page.waitForFunction((s) => document.querySelector(s).options.length === 1269, `${S} select[data-lab="munsell-chips"]`);
  const chips = ['5R4/14', '10YR6/10', '5Y8/10', '5G5/8', '5B5/6', '5PB4/10', '5P4/10', 'N5'];
  const listed = await page.$$eval(`${S} select[data-lab="munsell-chips"] option`, (o) => o.map((x) => x.value));
  const picked = chips.filter((c) => listed.includes(c)).slice(0, 7);   // 7 chips: a 2 × 4 grid, R2C4 empty
  assert.equal(picked.length, 7, `chips in the engine's list: ${picked}`);
  await page.selectOption(`${S} select[data-lab="munsell-chips"]`, picked);
  await page.click(`${S} [data-action="lab-render"]`);
  await page.waitForFunction(() => window.tristim.derived.labTruth?.layout, null, { timeout: 60000 });
  const truth = await page.evaluate(() => window.tristim.derived.labTruth);
  assert.deepEqual([truth.layout.rows, truth.layout.columns], [2, 4]);
  assert.deepEqual(truth.patches.map((p) => p.cell).slice(6), ['R2C3', 'R2C4']);
  assert.deepEqual(truth.patches.filter((p) => p.board).map((p) => p.id), ['R2C4']);
  assert.deepEqual(truth.noise, { shot_gain: 0, read_noise: 0, seed: truth.noise.seed });

  await page.click(`${S} [data-action="lab-open"]`);
  await page.waitForSelector('#step-images:not([hidden])');
  await waitSampled(page, truth.corners);
  const got = await page.evaluate(() => ({
    layout: window.tristim.session.layout,
    sample: window.tristim.derived.sample.patches.map((p) => ({ id: p.id, mean: Array.from(p.mean) })),
    note: document.querySelector('#step-images .detect-text').textContent,
    ref: window.tristim.derived.reference,
  }));
  assert.equal(got.layout.chart, 'custom');
  assert.deepEqual([got.layout.rows, got.layout.columns, got.layout.gap], [truth.layout.rows, truth.layout.columns, 0]);
  assert.match(got.note, /^Layout and corners from the render/);
  assert.match(got.note, /Cell R2C4 holds no chip: the chart's board/);
  assert.equal(got.sample.length, 8);
  // Every patch: the sampled camera RGB (DN above black) equal the truth's.
  const byId = new Map(got.sample.map((p) => [p.id, p.mean]));
  for (const p of truth.patches) {
    const m = byId.get(p.cell);
    assert.ok(m, `cell ${p.cell} (${p.id}) sampled`);
    p.rgb.forEach((v, c) => assert.ok(Math.abs(m[c] - v) <= 1e-6, `${p.id} ${'RGB'[c]}: sampled ${m[c]}, truth ${v}`));
  }
  // Step 1: the render's XYZ of each cell.
  assert.deepEqual(got.ref.ids, truth.patches.map((p) => p.cell));
  truth.patches.forEach((p, i) => p.XYZ.forEach((v, c) => assert.ok(Math.abs(got.ref.XYZ[3 * i + c] - v) <= 1e-9 * Math.max(1, v), `${p.id} XYZ`)));
  await screenshot(page, 'lab-grid-journey-images');

  await fitMatrix3x3(page);
});

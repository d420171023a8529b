// A second chart image in the Images step (issue 48, docs/multi-image.md): the user adds another
// photograph, the page finds its chart and samples it, and the Fit trains on both charts' patches.
// The page's coefficients equal `tristim fit --recipe` (the recipe the profile embeds, with its
// `images` list) on the same two files to the bit; the Results step shows each chart's training,
// leave-one-out and held-out figures; the exported profile records both images.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { pageTest, step, upload, fileBuffer, fitMatrix3x3, DNG } from './journey.mjs';
import { assertCliEqual } from './several_charts_common.mjs';

const PANEL = '#step-images fieldset.second-chart';

pageTest('a second chart image: one fit on both charts, equal to tristim fit --recipe with two --raw', { timeout: 240000 }, async ({ page }) => {
  await step(page, 'images');
  await upload(page, `${PANEL} input[data-slot="chart2"]`, 'second.dng', fileBuffer(DNG));
  await page.waitForFunction((sel) => document.querySelector(sel)?.dataset.state === 'sampled', PANEL, { timeout: 60000 });
  assert.match(await page.textContent(`${PANEL} .detect-text`), /Corners found automatically/);
  assert.equal(await page.locator(`${PANEL} .patch-table tbody tr`).count(), 24);
  assert.equal(await page.inputValue(`${PANEL} select[data-role="chart2-chart"]`), 'passport', 'the first image\'s chart by default');
  await page.selectOption(`${PANEL} select[data-role="duplicates"]`, 'each');   // both shots as rows of their own
  await screenshot(page, 'several-charts-1-images');

  await fitMatrix3x3(page);
  assert.match(await page.textContent('#step-fit .summary'), /and the 24 patches of the second chart image \(second\.dng/);
  const result = await page.evaluate(() => {
    const t = window.tristim;
    const r = t.session.results.find((x) => x.key === t.session.selected);
    return { profile: r.fit.profile, ids: Array.from(r.ids), charts: r.fit.charts };
  });
  assert.equal(result.ids.length, 48 - (await page.evaluate(() => window.tristim.session.results[0].recipe.images
    .reduce((n, e) => n + e.sampling.exclude.length, 0))));
  assert.deepEqual(result.charts.map((c) => c.chart), ['passport.dng', 'second.dng']);
  assert.ok(result.charts.every((c) => c.loo && c.held_out), 'per-chart leave-one-out and held-out figures');

  // The Results step: one row per chart with its figures.
  await step(page, 'results');
  const rows = page.locator('#step-results table.chart-figures tbody tr');
  assert.equal(await rows.count(), 2);
  assert.match(await rows.nth(1).textContent(), /^2: second\.dng24\d+\.\d\d/);
  await screenshot(page, 'several-charts-2-results');

  // The CLI on the recipe the profile embeds, with the two files in its order.
  const profile = JSON.parse(result.profile);
  assert.deepEqual(profile.recipe.images.map((e) => e.name), ['passport.dng', 'second.dng']);
  assert.ok(profile.recipe.images.every((e) => /^[0-9a-f]{64}$/.test(e.sha256)), 'each image recorded with its SHA-256');
  assertCliEqual(profile, result.charts, ['--raw', DNG, '--raw', DNG], 'several-charts');
});

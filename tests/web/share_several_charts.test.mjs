// The Share link of a fit on two chart images (issue 48, docs/multi-image.md): the link carries the
// union of both charts' patches (ids "k:A1", the union's reference XYZ inline) and a recipe listing
// both images; a fresh browser opening it recomputes the same profile — coefficients equal to the
// bit — and shows the two images. The Results swatches of such a fit show the reference colours
// ("k:A1" is the k-th image's chart's A1), not grey.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { pageTest, step, upload, fileBuffer, fitMatrix3x3, DNG } from './journey.mjs';
import { openShared, greySwatches } from './several_charts_common.mjs';

const PANEL = '#step-images fieldset.second-chart';

pageTest('two chart images: the link reproduces the two-image profile to the bit; swatches in colour', { timeout: 300000 }, async ({ page }) => {
  // As tests/web/several_charts.test.mjs: the example's DNG again as the second image.
  await step(page, 'images');
  await upload(page, `${PANEL} input[data-slot="chart2"]`, 'second.dng', fileBuffer(DNG));
  await page.waitForFunction((sel) => document.querySelector(sel)?.dataset.state === 'sampled', PANEL, { timeout: 60000 });
  await page.selectOption(`${PANEL} select[data-role="duplicates"]`, 'each');
  await fitMatrix3x3(page);
  const made = await page.evaluate(() => {
    const t = window.tristim, r = t.session.results.find((x) => x.key === t.session.selected);
    return { profile: JSON.parse(r.fit.profile), ids: Array.from(r.ids) };
  });
  assert.ok(made.ids.some((id) => id.startsWith('2:')), 'the fit holds the second image\'s patches');

  // Results: every swatch has its reference colour (none of the grey of an unknown id).
  const grey = await greySwatches(page);
  assert.deepEqual(grey, [], 'no grey reference swatch');

  await step(page, 'share');
  await page.click('#share-make');
  await page.waitForFunction(() => document.getElementById('share-link').value.includes('#tristim='), null, { timeout: 120000 });
  const link = await page.inputValue('#share-link');

  await openShared(link, async (fresh) => {
    assert.deepEqual(await fresh.$$eval('#share-verdict .share-charts li', (li) => li.map((x) => x.textContent)), ['1: passport.dng', '2: second.dng']);
    const again = await fresh.evaluate(async (text) => {
      const r = await window.tristim.engine.call('openLink', { text });
      return { profile: JSON.parse(r.profile), payload: JSON.parse(r.payload) };
    }, link);
    assert.deepEqual(again.payload.recipe.images.map((e) => e.name), ['passport.dng', 'second.dng'], 'the link\'s recipe lists both images');
    assert.equal(again.payload.patches.ids.length, made.ids.length, 'the union\'s patches');
    assert.ok(again.payload.patches.XYZ?.length === 3 * made.ids.length, 'the union\'s reference XYZ inline');
    assert.deepEqual(again.payload.sources.map((s) => s.name), ['passport.dng', 'second.dng']);
    assert.deepEqual(again.profile.model.coefficients, made.profile.model.coefficients, 'the two-image coefficients, to the bit');
    await screenshot(fresh, 'share-several-charts');
  });
});

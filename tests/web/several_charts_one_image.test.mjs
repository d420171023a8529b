// Two charts in one image (issue 48, docs/multi-image.md): the Images step's detection finds both
// ColorCheckers of a photograph, "Use both charts found" makes the second one the second chart,
// and the Fit trains on both. The page's coefficients equal `tristim fit --recipe` on the recipe
// the profile embeds (the same file twice, each entry with its own corners) to the bit; a reload
// keeps the second chart, and the Share link reproduces the fit in a fresh browser.
// The photograph is made at test time: two `tristim lab render` TIFFs (linear, 16 bit, one strip)
// of a ColorChecker at two places and two exposures, the left half of one and the right half of the
// other spliced into one file.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, upload, fitMatrix3x3, waitReady, CLI, artifact } from './journey.mjs';
import { assertCliEqual, openShared } from './several_charts_common.mjs';

const PANEL = '#step-images fieldset.second-chart';
const BOTH = '#step-images .detect-panel button.use-both';

/// The pixel strip of a one-strip baseline TIFF: [offset, byteCount] (tags 273, 279).
function strip(bytes) {
  const v = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const ifd = v.getUint32(4, true), tags = {};
  for (let i = 0, n = v.getUint16(ifd, true); i < n; i++) {
    const at = ifd + 2 + 12 * i;
    tags[v.getUint16(at, true)] = { count: v.getUint32(at + 4, true), value: v.getUint32(at + 8, true) };
  }
  assert.equal(tags[273].count, 1, 'one strip');
  return [tags[273].value, tags[279].value];
}

/// two.tiff: a ColorChecker left (exposure 0.3) and one right (0.2, slightly turned), 900 × 600.
function twoChartTiff() {
  const render = (name, exposure, corners) => {
    const out = artifact(name);
    execFileSync(CLI, ['lab', 'render', '--camera', 'Canon_EOS_5D_Mark_II', '--illuminant', 'D65', '--chart', 'cc24', '--size', '900x600',
      '--exposure', exposure, '--corners', corners, '--oecf', 'linear', '--out', out], { stdio: 'pipe' });
    return fs.readFileSync(out);
  };
  const a = render('one-image-left.tiff', '0.3', '40,150,400,150,400,390,40,390');
  const b = render('one-image-right.tiff', '0.2', '480,180,860,160,870,420,490,430');
  const [offset, count] = strip(a), row = count / 600;
  const two = Buffer.from(a);
  for (let y = 0; y < 600; y++) b.copy(two, offset + y * row + row / 2, offset + y * row + row / 2, offset + (y + 1) * row);
  const file = artifact('two-charts.tiff');
  fs.writeFileSync(file, two);
  return file;
}

pageTest('two charts in one image: both sampled and fitted, equal to tristim fit --recipe with the file twice; the link reproduces it', { timeout: 300000 }, async ({ page }) => {
  const file = twoChartTiff();
  await step(page, 'images');
  await page.selectOption('#step-images select[data-role="layout"]', 'cc24');
  await upload(page, '#step-images input[data-slot="chart"]', 'two.tiff', fs.readFileSync(file));
  await page.waitForSelector(`${BOTH}:not([hidden])`, { timeout: 60000 });
  assert.match(await page.textContent(BOTH), /Use both charts found \(2 in this image\)/);
  await page.click(BOTH);
  await page.waitForFunction((sel) => document.querySelector(sel)?.dataset.state === 'sampled', PANEL, { timeout: 60000 });
  assert.equal(await page.locator(`${PANEL} .patch-table tbody tr`).count(), 24);
  assert.match(await page.textContent(`${PANEL} .file-state`), /the second chart in two\.tiff/);
  const corners = await page.evaluate(() => [window.tristim.session.corners, window.tristim.session.chart2.corners].map((c) => Array.from(c)));
  assert.ok(Math.abs(corners[0][0] - corners[1][0]) > 300, 'the two charts, not one twice');
  await page.selectOption(`${PANEL} select[data-role="duplicates"]`, 'each');
  await screenshot(page, 'several-charts-one-image');

  await fitMatrix3x3(page);
  assert.match(await page.textContent('#step-fit .summary'), /and the 24 patches of the second chart image \(two\.tiff: its second chart, step 2\)/);
  const made = await page.evaluate(() => {
    const t = window.tristim, r = t.session.results.find((x) => x.key === t.session.selected);
    return { profile: r.fit.profile, ids: Array.from(r.ids), charts: r.fit.charts };
  });
  assert.equal(made.ids.length, 48);
  assert.ok(made.charts.every((c) => c.loo && c.held_out), 'per-chart leave-one-out and held-out figures');

  // The CLI on the recipe the profile embeds: the same file for both entries, each with its corners.
  const profile = JSON.parse(made.profile);
  assert.deepEqual(profile.recipe.images.map((e) => e.name), ['two.tiff', 'two.tiff']);
  assert.deepEqual(profile.recipe.images.map((e) => e.sampling.corners), corners);
  assertCliEqual(profile, made.charts, ['--raw', file, '--raw', file], 'one-image');

  // A reload restores the second chart of the same image, sampled at its corners.
  await page.reload();
  await waitReady(page);
  await page.waitForFunction((sel) => document.querySelector(sel)?.dataset.state === 'sampled', PANEL, { timeout: 60000 });
  assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.derived.sample2.corners)), corners[1]);

  // The Share link: a fresh browser recomputes the same two-chart profile.
  await step(page, 'share');
  await page.click('#share-make');
  await page.waitForFunction(() => document.getElementById('share-link').value.includes('#tristim='), null, { timeout: 120000 });
  const link = await page.inputValue('#share-link');
  await openShared(link, async (fresh) => {
    const again = await fresh.evaluate(async (text) => JSON.parse((await window.tristim.engine.call('openLink', { text })).profile), link);
    assert.deepEqual(again.model.coefficients, profile.model.coefficients, 'the link\'s coefficients, to the bit');
  });

  // A second image file replaces the first image's second chart: its own chart picker and frames.
  await step(page, 'images');
  await upload(page, `${PANEL} input[data-slot="chart2"]`, 'left.tiff', fs.readFileSync(artifact('one-image-left.tiff')));
  await page.waitForFunction((sel) => {
    const p = document.querySelector(sel), c2 = window.tristim.session.chart2, s2 = window.tristim.derived.sample2;
    return p?.dataset.state === 'sampled' && p.querySelector('.file-state').textContent.startsWith('left.tiff') && !c2.sameImage
      && c2.corners && s2 && Array.from(s2.corners).every((v, i) => v === c2.corners[i]);
  }, PANEL, { timeout: 60000 });
  assert.equal(await page.isEnabled(`${PANEL} select[data-role="chart2-chart"]`), true);
  assert.equal(await page.isVisible(`${PANEL} input[data-slot="dark2"]`), true);
});

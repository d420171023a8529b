// A chart cut by the frame (issue 48) on the page: the example Passport DNG with its sensor rows
// below 880 cut off (cut_chart_fixture.mjs: the chart's bottom row D lies outside the image). The page samples the patches inside, lists the others as "outside the
// frame" in the patch table, and fits on the rest — the fit `tristim fit --rgb cut.csv --xyz
// passport` makes of the page's own sampled rows. Corners that put every patch outside the image
// are refused with CORNERS_OUTSIDE.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, fitMatrix3x3, errorNear, CLI, artifact } from './journey.mjs';
import { openCutChart } from './cut_chart_fixture.mjs';
const TABLE = '#step-images .images-layout .patch-table';

pageTest('a chart cut by the frame: the patches inside are sampled, the others named, the fit uses the rest', { timeout: 180000 }, async ({ page }) => {
  // Detection finds the cut chart and names its patches outside the image; then the example's
  // corners: rows A–C inside the image, row D below its edge.
  await openCutChart(page);
  const s = await page.evaluate(() => { const x = window.tristim.derived.sample; return { ids: x.ids, missing: x.missing, RGB: Array.from(x.RGB), flags: x.flags }; });
  assert.deepEqual(s.missing, ['D1', 'D2', 'D3', 'D4', 'D5', 'D6']);
  assert.equal(s.ids.length, 18);
  assert.equal(await page.locator(`${TABLE} tbody tr.missing`).count(), 6);
  assert.match(await page.textContent(`${TABLE} tr.missing[data-id="D1"]`), /outside the frame/);
  assert.match(await page.textContent('#step-images .summary'), /18 patches sampled; .*6 outside the frame/);
  await screenshot(page, 'cut-chart-1-table');

  await fitMatrix3x3(page);
  assert.match(await page.textContent('#step-fit .summary'), /outside the frame \(not sampled\): D1, D2/);
  const fit = await page.evaluate(() => {
    const t = window.tristim, r = t.session.results.find((x) => x.key === t.session.selected);
    return { ids: Array.from(r.ids), coefficients: JSON.parse(r.fit.profile).model.coefficients };
  });
  // The CLI on the same rows (the page's sampled RGB, less what the page left out as saturated).
  const rows = s.ids.map((id, i) => [id, ...s.RGB.slice(3 * i, 3 * i + 3)]).filter(([id]) => fit.ids.includes(id));
  assert.equal(rows.length, fit.ids.length);
  const csv = artifact('cut-chart-rgb.csv'), out = artifact('cut-chart-cli.json');
  fs.writeFileSync(csv, ['patch,R,G,B', ...rows.map((r) => r.join(','))].join('\n') + '\n');
  execFileSync(CLI, ['fit', '--rgb', csv, '--xyz', 'passport', '--model', 'matrix-3x3', '--objective', 'ls', '--out', out], { stdio: 'pipe' });
  const cli = JSON.parse(fs.readFileSync(out, 'utf8')).model.coefficients;
  cli.flat().forEach((c, k) => assert.ok(Math.abs(c - fit.coefficients.flat()[k]) <= 1e-12 * Math.abs(c), `coefficient ${k}: CLI ${c}, page ${fit.coefficients.flat()[k]}`));

  // Corners that put every patch outside the image: refused, coded, next to the corners.
  await step(page, 'images');
  await page.evaluate(() => { const ed = window.tristim.views.images.editor; ed.setCorners(ed.corners.map((v, i) => (i % 2 ? v + 1000 : v))); ed.onChange(ed.corners, true); });
  assert.equal((await errorNear(page, '#step-images .corner-editor')).code, 'CORNERS_OUTSIDE');
});

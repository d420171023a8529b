// A chart cut by the frame (issue 48) on the page: the example Passport DNG with its sensor rows
// below 880 cut off (raw_fixtures.withSize: the header says 880 rows, so the chart's bottom row D
// lies outside the image). The page samples the patches inside, lists the others as "outside the
// frame" in the patch table, and fits on the rest — the fit `tristim fit --rgb cut.csv --xyz
// passport` makes of the page's own sampled rows. Corners that put every patch outside the image
// are refused with CORNERS_OUTSIDE.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, upload, fileBuffer, setCorners, fitMatrix3x3, errorNear, CLI, artifact, DNG } from './journey.mjs';
import { ifd0, withSize } from './raw_fixtures.mjs';
import { EXAMPLE } from './image_fixtures.mjs';

const dng = fileBuffer(DNG);
const { dv, entries } = ifd0(dng);
const e = entries[256];
const sensorWidth = e.type === 3 ? dv.getUint16(e.at, true) : dv.getUint32(e.at, true);
const CUT = withSize(dng, sensorWidth, 880);   // the measurement image: 427 rows (half resolution, less the crop)
const TABLE = '#step-images .images-layout .patch-table';

pageTest('a chart cut by the frame: the patches inside are sampled, the others named, the fit uses the rest', { timeout: 180000 }, async ({ page }) => {
  await step(page, 'images');
  await upload(page, '#step-images input[data-slot="chart"]', 'cut.dng', Buffer.from(CUT));
  await page.waitForFunction(() => window.tristim.derived.image?.height === 427, null, { timeout: 60000 });
  // Detection finds the cut chart and names its patches outside the image.
  await page.waitForFunction(() => window.tristim.derived.sample?.missing?.length === 6, null, { timeout: 60000 });
  // The example's corners: rows A–C inside the image, row D below its edge.
  await setCorners(page, EXAMPLE.corners);
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

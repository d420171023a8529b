// Journey: the Absolute mode (Guarnera, Bianco & Schettini 2018) with the engine's generated
// brackets. "Example" generates five exposures of a scene with known X, Y, Z, lens-cap frames, a
// flat and the training stimuli; the page fits the profile, draws the OECFs per channel and
// exposure, the luminance map with its cd/m² colour bar and the source-exposure map; the pointer
// read-out over the white patch is checked against the known stimulus (the paper's 2.4 %). Bad
// inputs show their codes next to the input that caused them.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { screenshot } from './harness.mjs';
import { step, upload, errorNear, markCounts, DNG, CR2, filePath, pageTest } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

const S = '#step-absolute';

pageTest('absolute: example bracket fitted, OECF curves, luminance map, read-out against the known stimulus, coded bad inputs', async ({ page }) => {
  const T = await loadTristim();
  const ex = T.absoluteExample();   // the page's example (same defaults): the truth of every cell
  await step(page, 'absolute');
  await page.click(`${S} [data-role="abs-example"]`);
  await page.waitForSelector(`${S} .abs-maps:not([hidden])`, { timeout: 180000 });

  // the fit: the planted OECF exponents (1.03, 1, 0.97) in the table, reciprocity holds
  for (const [c, k3] of [['R', 1.03], ['G', 1.0], ['B', 0.97]]) {
    const shown = Number(await page.textContent(`${S} td[data-col="k3-${c}"]`));
    assert.ok(Math.abs(shown - k3) < 0.01, `k3 ${c}: ${shown} vs ${k3}`);
  }
  assert.match(await page.textContent(`${S} [data-role="abs-reciprocity"]`), /Reciprocity holds/);
  // fig 5: points and curves in five exposure panels
  const counts = await markCounts(page, 'absolute-oecf');
  assert.ok(counts.dot > 5 * 3 * 10, `OECF points: ${JSON.stringify(counts)}`);
  assert.ok(counts.line >= 5 * 3, `OECF curves: ${JSON.stringify(counts)}`);
  const facets = await page.$$eval(`${S} figure[data-plot="absolute-oecf"] svg [aria-label="fx-axis tick label"] text`, (ts) => ts.map((t) => t.textContent));
  assert.deepEqual(facets, Array.from(ex.labels));

  // the maps: a log colour bar in cd/m², five exposures in the source legend
  const bar = await page.$eval(`${S} [data-role="abs-colourbar"] .legend-box`, (e) => ({ ...e.dataset, text: e.textContent }));
  assert.equal(bar.scale, 'log');
  assert.match(bar.text, /cd\/m²/);
  assert.ok(Number(bar.low) > 0.01 && Number(bar.high) > 1000, JSON.stringify(bar));
  assert.equal(await page.$$eval(`${S} [data-role="abs-source-legend"] li`, (l) => l.length), 6);
  const distinct = await page.$eval(`${S} canvas[data-role="abs-luminance"]`, (c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data, seen = new Set();
    for (let i = 0; i < d.length; i += 4) seen.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
    return seen.size;
  });
  assert.ok(distinct > 30, `${distinct} colours in the luminance map`);

  // the read-out over the white patch's centre: the known stimulus within 2.4 %
  const white = ex.regions.find((r) => r.id === ex.white_id);
  const box = await page.$eval(`${S} canvas[data-role="abs-luminance"]`, (c) => { c.scrollIntoView({ block: 'center' }); const r = c.getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; });
  const W = ex.frames[0].width(), H = ex.frames[0].height();
  await page.mouse.move(box.x + ((white.x + white.w / 2 + 0.5) / W) * box.w, box.y + ((white.y + white.h / 2 + 0.5) / H) * box.h);
  await page.waitForFunction((s) => document.querySelector(`${s} [data-role="abs-readout"]`)?.dataset.region, `${S}`);
  const r = await page.$eval(`${S} [data-role="abs-readout"]`, (e) => ({ ...e.dataset, text: e.textContent }));
  assert.equal(r.region, ex.white_id);
  for (const [k, c] of [['X', 0], ['Y', 1], ['Z', 2]]) {
    const rel = Number(r[k]) / white.XYZ[c] - 1;
    assert.ok(Math.abs(rel) < 0.024, `read-out ${k} ${r[k]} vs known ${white.XYZ[c]} (${(100 * rel).toFixed(2)} %)`);
  }
  assert.match(r.text, /cd\/m²/);
  assert.match(r.text, /source exposure 1\/\d+ s f\/8/);
  // the section 4.1 figures on the scene's cells
  const relY = await page.$$eval(`${S} [data-role="abs-figures"] [data-col="relY"]`, (e) => e.map((x) => parseFloat(x.textContent)));
  assert.equal(relY.length, 4);   // training, all cells, ColorChecker cells, ladder
  assert.ok(relY[1] < 2.4, `relative Y error on the scene's cells ${relY[1]} %`);
  await screenshot(page, 'absolute-1-example');

  // downloads: the absolute profile JSON, and the X, Y, Z map as a float TIFF whose white-patch
  // centre holds the known stimulus within 2.4 %
  const [dlProfile] = await Promise.all([page.waitForEvent('download'), page.click(`${S} [data-role="abs-download-profile"]`)]);
  const profile = JSON.parse(fs.readFileSync(await dlProfile.path(), 'utf8'));
  assert.equal(typeof profile, 'object');
  assert.match(dlProfile.suggestedFilename(), /absolute\.json$/);
  const [dlTiff] = await Promise.all([page.waitForEvent('download'), page.click(`${S} [data-role="abs-download-xyz"]`)]);
  const tiff = fs.readFileSync(await dlTiff.path());
  assert.equal(tiff.toString('latin1', 0, 4), 'II*\0');
  const dv = new DataView(tiff.buffer, tiff.byteOffset, tiff.byteLength), ifd = dv.getUint32(4, true);
  const tags = {};
  for (let i = 0; i < dv.getUint16(ifd, true); i++) { const e = ifd + 2 + 12 * i; tags[dv.getUint16(e, true)] = dv.getUint32(e + 8, true); }
  assert.equal(tags[256], W);
  let ySum = 0;  // mean Y over 5 × 5 pixels at the white patch's centre
  for (let dy = -2; dy <= 2; dy++)
    for (let dx = -2; dx <= 2; dx++) ySum += dv.getFloat32(tags[273] + (((white.y + white.h / 2 + dy) * W + white.x + white.w / 2 + dx) * 3 + 1) * 4, true);
  assert.ok(Math.abs(ySum / 25 / white.XYZ[1] - 1) < 0.024, `TIFF Y at the white patch ${ySum / 25} vs known ${white.XYZ[1]}`);

  // linear colour bar on request
  await page.click(`${S} [data-role="abs-log"]`);
  await page.waitForFunction((s) => document.querySelector(`${s} [data-role="abs-colourbar"] .legend-box`)?.dataset.scale === 'linear', S);

  // exposure times shown as the camera shows them; a typed fraction is read as one, and a typo is
  // refused next to the series (it used to read as "from the metadata" without a word)
  const tBoxes = await page.$$eval(`${S} input[aria-label^="exposure time of"]`, (e) => e.map((x) => x.value));
  assert.deepEqual(tBoxes, Array.from(ex.labels, (l) => l.split(' ')[0]));
  const tBox = `${S} input[aria-label^="exposure time of virtual-2"]`;
  await page.fill(tBox, '1/12o');
  await page.press(tBox, 'Tab');
  const typo = await errorNear(page, `${S} [data-role="abs-series"]`);
  assert.equal(typo.code, 'INVALID_ARGUMENT');
  assert.match(typo.text, /virtual-2\.raw.*'1\/12o'/);
  await page.fill(tBox, '1/125');
  await page.press(tBox, 'Tab');
  await page.waitForFunction((s) => { const el = document.querySelector(`${s} [data-role="abs-series"]`); return document.getElementById(el.getAttribute('aria-describedby'))?.hidden; }, S);

  // bad inputs, each next to its input: stimuli without X, Y, Z; non-monotonic stimuli; a series of two cameras
  await upload(page, `${S} [data-role="abs-stimuli"]`, 'no-xyz.csv', Buffer.from('id,exposure_s,f_number,R,G,B\n1,0.01,8,10,20,30\n'));
  assert.equal((await errorNear(page, `${S} [data-role="abs-stimuli"]`)).code, 'MISSING_COLUMN');
  const rows = ex.stimuli_csv.trim().split('\n');
  const header = rows[0].split(','), col = (n) => header.indexOf(n), at = (id) => rows.findIndex((x) => x.startsWith(`${id},`));
  const a = rows[at('Y300@3')].split(','), c = rows[at('Y600@3')].split(',');
  for (const k of ['R', 'G', 'B']) [a[col(k)], c[col(k)]] = [c[col(k)], a[col(k)]];
  rows[at('Y300@3')] = a.join(','); rows[at('Y600@3')] = c.join(',');
  await upload(page, `${S} [data-role="abs-stimuli"]`, 'swapped.csv', Buffer.from(rows.join('\n')));
  await page.waitForFunction((s) => /swapped\.csv/.test(document.querySelector(`${s} [data-role="abs-stimuli-info"]`)?.textContent ?? ''), S);
  await page.click(`${S} [data-role="abs-fit"]`);
  const nm = await errorNear(page, `${S} [data-role="abs-stimuli"]`);
  assert.equal(nm.code, 'NON_MONOTONIC');
  assert.match(nm.text, /Y600@3|Y300@3/);
  await page.setInputFiles(`${S} [data-role="abs-series"]`, [filePath(DNG), filePath(CR2)]);
  const fm = await errorNear(page, `${S} [data-role="abs-series"]`, 60000);
  assert.equal(fm.code, 'FRAME_MISMATCH');
  assert.match(fm.text, /IMG_5952/);
  await screenshot(page, 'absolute-2-bad-input');
  for (const f of [...ex.frames, ...ex.lens_cap, ex.flat]) f.delete();
});

// Bad inputs from the RAW and models issues: each shows its coded message next to the control that
// caused it (the test asserts the code, not the words), and the page recovers: the last good state
// stays, and the next good input works. Bad RAW files are made at test time (raw_fixtures.mjs).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { screenshot } from './harness.mjs';
import { step, upload, fileBuffer, errorNear, errorFor, noErrorNear, DNG, CR2, JPEG, fixture, pageTest } from './journey.mjs';
import { withSize, withZeroRows, twoLevelFlat } from './raw_fixtures.mjs';

const CHART = '#step-images input[data-slot="chart"]';
const DARK = '#step-images input[data-slot="dark"]';
const FLAT = '#step-images input[data-slot="flat"]';
const REF = '#step-reference input[type=file]';
const FIT = '#step-fit button.primary';
const A1 = '#step-images .patch-table tbody tr[data-id="A1"]';
const rowCount = (page) => page.locator('#step-images .patch-table tbody tr').count();
const fileState = (page, sel) => page.evaluate((s) => document.querySelector(s).closest('.field-group').querySelector('.file-state').textContent, sel);

/// Ticks exactly the given models (by id) and the first objective.
async function choose(page, modelIds) {
  const models = page.locator('#step-fit input[data-model]');
  for (let i = 0; i < await models.count(); i++) await models.nth(i).setChecked(modelIds.includes(await models.nth(i).getAttribute('data-model')));
  const objs = page.locator('#step-fit input[data-objective]');
  for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(i === 0);
}
/// Clicks "Fit selected" and waits for the run to end (the fit log's summary line).
async function fit(page) {
  await page.click(FIT);
  await page.waitForFunction(() => /fits in [\d.]+ s\.$/.test(document.querySelector('#step-fit .fit-log li:last-child')?.textContent ?? '')
    || !document.getElementById('fit-error')?.hidden, null, { timeout: 60000 });
}

pageTest('bad RAW files, corners and calibration frames: coded errors next to their control, the page recovers', async ({ page }) => {
  await step(page, 'images');
  assert.equal(await rowCount(page), 24, 'the example chart is sampled');
  const plainA1 = await page.textContent(A1);
  const dng = fileBuffer(DNG);
  const jpeg = fileBuffer(JPEG);   // a real JPEG: its first half, renamed .CR2 (decoded by signature, not by name)
  const cases = [
    ['empty.dng', Buffer.alloc(0), 'EMPTY_FILE'],
    ['truncated.dng', dng.subarray(0, 1 << 20), 'RAW_TRUNCATED'],
    ['half-jpeg.CR2', jpeg.subarray(0, jpeg.length >> 1), 'IMAGE_CORRUPT'],
    ['animation.gif', Buffer.from('GIF89a\x01\x00\x01\x00\x00\x00\x00;', 'latin1'), 'IMAGE_UNSUPPORTED'],
    ['random.NEF', Buffer.from(Array.from({ length: 65536 }, (_, i) => (i * 2654435761) >>> 24)), 'RAW_UNSUPPORTED'],
    // The Passport DNG's first 64 KiB with a header claiming 60000 × 60000 pixels.
    ['absurd-size.dng', withSize(dng, 60000, 60000, { keepBytes: 1 << 16 }), 'RAW_TOO_LARGE'],
  ];
  const codes = {};
  for (const [name, bytes, code] of cases) {
    await upload(page, CHART, name, Buffer.from(bytes));
    const e = await errorFor(page, CHART, name);
    codes[name] = e.code;
    assert.equal(e.code, code, `${name}: ${e.text}`);
    // The previous image and its table are still there.
    assert.equal(await rowCount(page), 24);
    assert.equal(await page.textContent(A1), plainA1);
  }
  await screenshot(page, 'bad-input-raw');

  const setCorners = (cs) => page.evaluate((v) => { const ed = window.tristim.views.images.editor; ed.setCorners(v); ed.onChange(ed.corners, true); }, cs);
  const cornerCode = (not) => page.waitForFunction((n) => {
    const slot = document.getElementById('corners-error');
    return slot && !slot.hidden && slot.dataset.code && slot.dataset.code !== n ? slot.dataset.code : null;
  }, not).then((h) => h.jsonValue());
  const before = await page.evaluate(() => Array.from(window.tristim.session.corners));
  const [x0, y0, x1, y1, x2, y2, x3, y3] = before;
  // Crossed corners (top-right and bottom-right swapped).
  await setCorners([x0, y0, x2, y2, x1, y1, x3, y3]);
  codes.crossed = await cornerCode(null);
  assert.equal(codes.crossed, 'CORNERS_CROSSED');
  assert.equal(await page.getAttribute('#step-images .corner-editor', 'aria-describedby'), 'corners-error');
  await screenshot(page, 'bad-input-crossed-corners');
  // Corners outside the image: the chart shifted off the left edge, every patch outside (a chart
  // only partly outside is sampled where it is inside: tests/web/cut_chart.test.mjs).
  await setCorners([x0 - 1000, y0, x1 - 1000, y1, x2 - 1000, y2, x3 - 1000, y3]);
  codes.outside = await cornerCode('CORNERS_CROSSED');
  assert.equal(codes.outside, 'CORNERS_OUTSIDE');
  // Patches smaller than 4 pixels.
  await setCorners([x0, y0, x0 + 6, y0, x0 + 6, y0 + 4, x0, y0 + 4]);
  codes.tiny = await cornerCode('CORNERS_OUTSIDE');
  assert.equal(codes.tiny, 'PATCH_TOO_SMALL');
  // Recovery: good corners clear the error and sample again.
  await setCorners(before);
  await page.waitForFunction(() => document.getElementById('corners-error')?.hidden === true);
  assert.equal(await rowCount(page), 24);
  assert.equal(await page.textContent(A1), plainA1);

  // Dark frames that do not fit the chart image: another camera (the CR2), and the same camera
  // at another size (the Passport DNG's header cut to 800 sensor rows). Both are refused.
  await upload(page, DARK, 'other-camera.CR2', fileBuffer(CR2));
  codes.darkCamera = (await errorFor(page, DARK, 'other-camera.CR2')).code;
  assert.equal(codes.darkCamera, 'FRAME_MISMATCH');
  await upload(page, DARK, 'same-camera-800-rows.dng', Buffer.from(withSize(dng, 1888, 800)));
  codes.darkSize = (await errorFor(page, DARK, 'same-camera-800-rows.dng')).code;
  assert.equal(codes.darkSize, 'FRAME_MISMATCH');
  assert.equal(await fileState(page, DARK), '');
  assert.equal(await page.textContent(A1), plainA1);

  // Flat fields: one with signal in every pixel (two levels) is applied; then one with 40 sensor
  // rows of zeros is refused and the first stays in use, in the page and in the worker.
  const flat = twoLevelFlat(dng, 100);
  await upload(page, FLAT, 'good-flat.dng', Buffer.from(flat));
  await page.waitForFunction(() => /good-flat\.dng — .*flat field \(pixel\) applied/.test(document.querySelector('#step-images input[data-slot="flat"]').closest('.field-group').textContent), null, { timeout: 60000 });
  await page.waitForFunction(([s, p]) => document.querySelector(s)?.textContent !== p, [A1, plainA1]);
  const flatA1 = await page.textContent(A1);
  await upload(page, FLAT, 'flat-with-zeros.dng', Buffer.from(withZeroRows(flat, 500, 540)));
  codes.flatZero = (await errorFor(page, FLAT, 'flat-with-zeros.dng')).code;
  assert.equal(codes.flatZero, 'FLAT_FIELD_ZERO');
  assert.match(await fileState(page, FLAT), /^good-flat\.dng/);
  assert.equal(await page.evaluate(() => window.tristim.session['files.flat'].name), 'good-flat.dng');
  const resampled = await page.evaluate(async () => (await window.tristim.views.images.resample())?.ids.length);
  assert.equal(resampled, 24);
  assert.equal(await page.textContent(A1), flatA1, 'the worker still applies the good flat');
  await screenshot(page, 'bad-input-frames');
  await page.click('#step-images .field-group:has(input[data-slot="flat"]) button:has-text("Remove")');
  await page.waitForFunction(([s, p]) => document.querySelector(s)?.textContent === p, [A1, plainA1]);

  // A good file after the bad ones decodes.
  await upload(page, CHART, 'good-again.dng', dng);
  await page.waitForFunction(() => /good-again\.dng — \d+×\d+/.test(document.querySelector('#step-images .file-state')?.textContent ?? ''), null, { timeout: 60000 });
  assert.ok(await noErrorNear(page, CHART));
  assert.equal(await rowCount(page), 24);
  console.log('bad RAW input codes', codes);
});

pageTest('bad reference, patch and profile files and impossible fits: coded errors next to their control, the page recovers', async ({ page }) => {
  const codes = {};
  await step(page, 'reference');
  const summary = await page.textContent('#step-reference .summary');
  // Malformed (a non-numeric cell) and NaN in a reference CSV: refused, the built-in reference stays.
  await upload(page, REF, 'malformed_Lab.csv', fs.readFileSync(fixture('malformed_Lab.csv')));
  codes.malformed = (await errorFor(page, REF, 'malformed_Lab.csv')).code;
  assert.equal(codes.malformed, 'NON_NUMERIC');
  const nan = fs.readFileSync(fixture('cc24_Lab_D50.csv'), 'utf8').replace(/^B2,[^,\n]+,/m, 'B2,NaN,');
  assert.match(nan, /^B2,NaN,/m);
  await upload(page, REF, 'nan_Lab.csv', Buffer.from(nan));
  codes.nan = (await errorFor(page, REF, 'nan_Lab.csv')).code;
  assert.equal(codes.nan, 'NON_FINITE');
  assert.equal(await page.textContent('#step-reference .summary'), summary);

  // Negative XYZ: the file is a valid table, the fit refuses it (NEGATIVE_VALUE).
  const xyzCsv = await page.evaluate(() => {
    const r = window.tristim.derived.reference;
    return 'patch,X,Y,Z\n' + r.ids.map((id, i) => `${id},${id === 'B2' ? -1 : r.XYZ[3 * i]},${r.XYZ[3 * i + 1]},${r.XYZ[3 * i + 2]}`).join('\n') + '\n';
  });
  await upload(page, REF, 'negative_XYZ.csv', Buffer.from(xyzCsv));
  await page.waitForFunction(() => /negative_XYZ\.csv/.test(document.querySelector('#step-reference .summary')?.textContent ?? ''));
  assert.ok(await noErrorNear(page, REF));
  await step(page, 'fit');
  await choose(page, ['matrix-3x3']);
  await fit(page);
  assert.equal((await errorNear(page, FIT)).code, 'FIT_FAILED');
  codes.negative = await page.getAttribute('#step-fit .fit-log li.error', 'data-code');
  assert.equal(codes.negative, 'NEGATIVE_VALUE');
  await screenshot(page, 'bad-input-fit-negative');

  // A reference whose ids are not the chart's (a custom grid's R1C1...): nothing pairs.
  const custom = xyzCsv.replace(/^([A-D])([1-6]),/gm, (_, r, c) => `R${'ABCD'.indexOf(r) + 1}C${c},`).replace(',-1,', ',10,');
  await step(page, 'reference');
  await upload(page, REF, 'custom_ids_XYZ.csv', Buffer.from(custom));
  await page.waitForFunction(() => /custom_ids_XYZ\.csv/.test(document.querySelector('#step-reference .summary')?.textContent ?? ''));
  await step(page, 'fit');
  await fit(page);
  codes.idsReference = (await errorNear(page, FIT)).code;
  assert.equal(codes.idsReference, 'PATCH_MISMATCH');

  // Back to the built-in reference: a held-out patch file whose ids are not the reference's.
  await step(page, 'reference');
  await page.click('#step-reference button:has-text("Use the built-in chart instead")');
  await page.waitForFunction((s) => document.querySelector('#step-reference .summary')?.textContent === s, summary);
  await step(page, 'fit');
  const held = '#step-fit input[type=file]';
  await upload(page, held, 'held-out-custom-ids.csv', Buffer.from('patch,R,G,B\n' + Array.from({ length: 24 }, (_, i) => `R${(i / 6 | 0) + 1}C${i % 6 + 1},${100 + i},${120 + i},${90 + i}`).join('\n') + '\n'));
  codes.idsHeldOut = (await errorFor(page, held, 'held-out-custom-ids.csv')).code;
  assert.equal(codes.idsHeldOut, 'PATCH_MISMATCH');

  // Too few patches: leave out every flagged patch (most are noisy here) and fit a 35-term polynomial.
  await page.check('#exclude-flagged');
  await choose(page, ['Cheung2004-35']);
  await fit(page);
  assert.equal((await errorNear(page, FIT)).code, 'FIT_FAILED');
  codes.tooFew = await page.getAttribute('#step-fit .fit-log li.error', 'data-code');
  assert.equal(codes.tooFew, 'TOO_FEW_PATCHES');
  await page.uncheck('#exclude-flagged');
  await screenshot(page, 'bad-input-fit');

  // Recovery: a good fit after the bad ones.
  await choose(page, ['matrix-3x3']);
  await page.click(FIT);
  await page.waitForFunction(() => document.querySelectorAll('#step-results:not([hidden]) table.compare tbody tr').length === 1, null, { timeout: 60000 });
  assert.ok(await noErrorNear(page, FIT));

  // A profile JSON of an unknown version, and one that is not JSON at all.
  await step(page, 'export');
  const imp = '#step-export input[type=file]';
  await upload(page, imp, 'future.json', Buffer.from(JSON.stringify({ format: 'tristim-profile', version: 99, model: { id: 'matrix-3x3' } })));
  codes.profileVersion = (await errorFor(page, imp, 'future.json')).code;
  assert.equal(codes.profileVersion, 'PROFILE_VERSION');
  await upload(page, imp, 'broken.json', Buffer.from('{"format": "tristim-profile", '));
  codes.profileJson = (await errorFor(page, imp, 'broken.json')).code;
  assert.equal(codes.profileJson, 'PARSE_ERROR');
  console.log('bad reference/fit input codes', codes);
});

// Bad inputs from the RAW and models issues: each shows a coded message next to the control that
// caused it, and the page recovers (the last good state stays, the next good input works).
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { screenshot } from './harness.mjs';
import { openPage, step, upload, fileBuffer, errorNear, noErrorNear, DNG, CR2, JPEG, fixture } from './journey.mjs';

const CHART = '#step-images input[data-slot="chart"]';
const rowCount = (page) => page.locator('#step-images .patch-table tbody tr').count();

test('bad inputs show coded errors next to their control and the page recovers', async () => {
  const b = await openPage();
  try {
    const { page } = b;
    await step(page, 'reference');
    await upload(page, '#step-reference input[type=file]', 'malformed_Lab.csv', fs.readFileSync(fixture('malformed_Lab.csv')));
    const e = await errorNear(page, '#step-reference input[type=file]');
    assert.notEqual(e.code, 'INTERNAL');
    await step(page, 'images');
    const good = await rowCount(page);
    assert.equal(good, 24, 'the example chart is sampled');
    const cases = [
      ['empty.dng', Buffer.alloc(0)],
      ['truncated.dng', fileBuffer(DNG, 1 << 20)],
      ['photo.CR2', fs.readFileSync(JPEG)],
      ['random.NEF', Buffer.from(Array.from({ length: 65536 }, (_, i) => (i * 2654435761) >>> 24))],
    ];
    const codes = {};
    for (const [name, bytes] of cases) {
      await upload(page, CHART, name, bytes);
      const e = await errorNear(page, CHART);
      assert.match(e.text, new RegExp(name.replace('.', '\\.')));
      assert.ok(e.code && e.code !== 'INTERNAL' && e.code !== 'ERROR', `${name}: coded error, got ${e.code}`);
      codes[name] = e.code;
      // The previous image and its table are still there.
      assert.equal(await rowCount(page), good);
    }
    await screenshot(page, 'bad-input-raw');

    const setCorners = (cs) => page.evaluate((v) => { const ed = window.tristim.views.images.editor; ed.setCorners(v); ed.onChange(ed.corners, true); }, cs);
    const before = await page.evaluate(() => Array.from(window.tristim.session.corners));
    // Crossed corners (top-right and bottom-right swapped).
    const [x0, y0, x1, y1, x2, y2, x3, y3] = before;
    await setCorners([x0, y0, x2, y2, x1, y1, x3, y3]);
    const crossed = await errorNear(page, '#step-images .corner-editor');
    assert.notEqual(crossed.code, 'INTERNAL');
    await screenshot(page, 'bad-input-crossed-corners');
    // Corners outside the image.
    await setCorners([x0 - 400, y0, x1 - 400, y1, x2 - 400, y2, x3 - 400, y3]);   // the chart shifted off the left edge
    await page.waitForFunction(() => document.getElementById('corners-error')?.dataset.code !== 'CORNERS_CROSSED');
    const outside = await errorNear(page, '#step-images .corner-editor');
    assert.equal(outside.code, 'CORNERS_OUTSIDE');
    // Patches smaller than 4 pixels.
    await setCorners([x0, y0, x0 + 6, y0, x0 + 6, y0 + 4, x0, y0 + 4]);
    const tiny = await errorNear(page, '#step-images .corner-editor');
    assert.notEqual(tiny.code, 'INTERNAL');
    codes.tiny = tiny.code;
    // Recovery: good corners clear the error and sample again.
    await setCorners(before);
    await page.waitForFunction(() => document.getElementById('corners-error')?.hidden === true);
    assert.equal(await rowCount(page), good);
    codes.crossed = crossed.code; codes.outside = outside.code;
    // A dark frame from another camera (the CR2) does not fit the chart image.
    await upload(page, '#step-images input[data-slot="dark"]', 'other-camera.CR2', fileBuffer(CR2));
    const dark = await errorNear(page, '#step-images input[data-slot="dark"]', 60000);
    assert.notEqual(dark.code, 'INTERNAL');
    codes.dark = dark.code;
    assert.equal(await rowCount(page), good);
    // A good file after the bad ones decodes.
    await upload(page, CHART, 'good-again.dng', fileBuffer(DNG));
    await page.waitForFunction(() => /good-again\.dng — \d+×\d+/.test(document.querySelector('#step-images .file-state')?.textContent ?? ''), null, { timeout: 60000 });
    assert.ok(await noErrorNear(page, CHART));
    // Too few patches: leave out every flagged patch (most are noisy here) and fit a 35-term polynomial.
    await step(page, 'fit');
    await page.check('#exclude-flagged');
    const models = page.locator('#step-fit input[data-model]');
    for (let i = 0; i < await models.count(); i++) await models.nth(i).setChecked(await models.nth(i).getAttribute('data-model') === 'Cheung2004-35');
    const objs = page.locator('#step-fit input[data-objective]');
    for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(i === 0);
    await page.click('#step-fit button.primary');
    const fitErr = await errorNear(page, '#step-fit button.primary');
    assert.equal(fitErr.code, 'FIT_FAILED');
    const line = await page.textContent('#step-fit .fit-log li.error');
    codes.fit = await page.getAttribute('#step-fit .fit-log li.error', 'data-code');
    assert.ok(codes.fit && codes.fit !== 'INTERNAL', line);
    await page.uncheck('#exclude-flagged');
    await screenshot(page, 'bad-input-fit');
    // A profile JSON of an unknown version, and one that is not JSON at all.
    await step(page, 'export');
    const imp = '#step-export input[type=file]';
    await upload(page, imp, 'future.json', Buffer.from(JSON.stringify({ format: 'tristim-profile', version: 99, model: { id: 'matrix-3x3' } })));
    const e1 = await errorNear(page, imp);
    await upload(page, imp, 'broken.json', Buffer.from('{"format": "tristim-profile", '));
    const e2 = await page.waitForFunction(() => /broken\.json/.test(document.getElementById(document.querySelector('#step-export input[type=file]').getAttribute('aria-describedby'))?.textContent ?? '')).then(() => errorNear(page, imp));
    assert.notEqual(e1.code, 'INTERNAL');
    assert.equal(e2.code, 'PARSE_ERROR');
    codes.profileVersion = e1.code; codes.profileJson = e2.code;
    console.log('bad-input codes', codes);
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});

// Bad inputs from the RAW and models issues: each shows a coded message next to the control that
// caused it, and the page recovers (the last good state stays, the next good input works).
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { screenshot } from './harness.mjs';
import { openPage, caps, step, upload, fileBuffer, errorNear, noErrorNear, DNG, CR2, JPEG, fixture } from './journey.mjs';

const CHART = '#step-images input[data-slot="chart"]';
const rowCount = (page) => page.locator('#step-images .patch-table tbody tr').count();

test('bad inputs show coded errors next to their control and the page recovers', async (t) => {
  const b = await openPage();
  try {
    const { page } = b;
    const c = await caps(page);
    if (c.parseReferenceFile) {
      await step(page, 'reference');
      await upload(page, '#step-reference input[type=file]', 'malformed_Lab.csv', fs.readFileSync(fixture('malformed_Lab.csv')));
      const e = await errorNear(page, '#step-reference input[type=file]');
      assert.notEqual(e.code, 'INTERNAL');
    }
    if (!c.decodeRaw) { t.skip('engine has no decodeRaw() yet'); return; }
    await step(page, 'images');
    const good = c.sampleChart ? await rowCount(page) : 0;
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
      if (c.sampleChart) assert.equal(await rowCount(page), good);
    }
    await screenshot(page, 'bad-input-raw');

    if (c.sampleChart && good) {
      const setCorners = (cs) => page.evaluate((v) => { const ed = window.tristim.views.images.editor; ed.setCorners(v); ed.onChange(ed.corners, true); }, cs);
      const before = await page.evaluate(() => Array.from(window.tristim.session.corners));
      // Crossed corners (top-right and bottom-right swapped).
      const [x0, y0, x1, y1, x2, y2, x3, y3] = before;
      await setCorners([x0, y0, x2, y2, x1, y1, x3, y3]);
      const crossed = await errorNear(page, '#step-images .corner-editor');
      assert.notEqual(crossed.code, 'INTERNAL');
      await screenshot(page, 'bad-input-crossed-corners');
      // Corners outside the image.
      await setCorners([-500, -500, x1, y1, x2, y2, x3, y3]);
      const outside = await errorNear(page, '#step-images .corner-editor');
      assert.notEqual(outside.code, 'INTERNAL');
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
    }
    // A dark frame from another camera (the CR2) does not fit the chart image.
    await upload(page, '#step-images input[data-slot="dark"]', 'other-camera.CR2', fileBuffer(CR2));
    const dark = await errorNear(page, '#step-images input[data-slot="dark"]', 60000);
    assert.notEqual(dark.code, 'INTERNAL');
    codes.dark = dark.code;
    if (c.sampleChart && good) assert.equal(await rowCount(page), good);
    // A good file after the bad ones decodes.
    await upload(page, CHART, 'passport.dng', fileBuffer(DNG));
    await page.waitForFunction(() => /passport\.dng — \d+×\d+/.test(document.querySelector('#step-images .file-state')?.textContent ?? ''), null, { timeout: 60000 });
    assert.ok(await noErrorNear(page, CHART));
    console.log('bad-input codes', codes);
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});

// Optional calibration frames: several dark frames are averaged by the engine; a flat field is
// applied per pixel or as a radial fall-off fit; removing them restores the plain sampling.
// (The chart DNG itself stands in for the frames here: same camera and size, so the engine accepts it.)
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { step, upload, fileBuffer, DNG, noErrorNear, pageTest } from './journey.mjs';

const A1 = '#step-images .patch-table tbody tr[data-id="A1"]';

pageTest('dark frames and flat field change the sampling and can be removed', async ({ page }) => {
  await step(page, 'images');
  await page.waitForSelector(A1);
  const plain = await page.textContent(A1);
  const dng = fileBuffer(DNG);
  const darkInput = '#step-images input[data-slot="dark"]';
  await page.setInputFiles(darkInput, [
    { name: 'dark1.dng', mimeType: 'application/octet-stream', buffer: dng },
    { name: 'dark2.dng', mimeType: 'application/octet-stream', buffer: dng },
  ]);
  await page.waitForFunction(() => /dark: 2 frame/.test(document.querySelector('#step-images input[data-slot="dark"]')?.closest('.field-group')?.textContent ?? ''), null, { timeout: 60000 });
  assert.ok(await noErrorNear(page, darkInput));
  await page.waitForFunction(([sel, p]) => document.querySelector(sel)?.textContent !== p, [A1, plain]);
  // The chart minus itself: every patch is near zero and flagged dark.
  assert.match(await page.textContent(A1), /dark/);
  await screenshot(page, 'frames-dark');
  await page.click('#step-images .field-group:has(input[data-slot="dark"]) button:has-text("Remove")');
  await page.waitForFunction(([sel, p]) => document.querySelector(sel)?.textContent === p, [A1, plain]);

  await page.selectOption('#step-images select >> nth=0', 'radial');
  await upload(page, '#step-images input[data-slot="flat"]', 'flat.dng', dng);
  await page.waitForFunction(() => /radial fall-off p1/.test(document.querySelector('#step-images input[data-slot="flat"]')?.closest('.field-group')?.textContent ?? ''), null, { timeout: 60000 });
  await page.waitForFunction(([sel, p]) => document.querySelector(sel)?.textContent !== p, [A1, plain]);
  await page.click('#step-images .field-group:has(input[data-slot="flat"]) button:has-text("Remove")');
  await page.waitForFunction(([sel, p]) => document.querySelector(sel)?.textContent === p, [A1, plain]);
});

// Journey 1 (issue 2, first page): the reference view for a chart, illuminant and observer;
// switching the illuminant changes the values; a good and a malformed reference upload.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { screenshot } from './harness.mjs';
import { step, upload, errorNear, noErrorNear, marks, fixture, pageTest } from './journey.mjs';

pageTest('reference: swatches and xy diagram follow the illuminant; uploads show values or a coded error', async ({ page }) => {
  await step(page, 'reference');
  await page.waitForSelector('#step-reference .swatch');
  const n = await page.locator('#step-reference .swatch').count();
  assert.ok(n >= 24, `expected at least 24 swatches, got ${n}`);
  const xyMarks = await marks(page, 'reference-xy');
  assert.ok(xyMarks >= n, `xy diagram should draw every patch (${xyMarks} marks)`);
  const before = await page.textContent('#step-reference .swatch[data-id="A1"]');

  // Switch the illuminant: the values must change.
  const illum = page.locator('#step-reference select').nth(1);
  const options = await illum.locator('option').evaluateAll((os) => os.map((o) => o.value));
  const other = options.find((v) => /^A$|^F11$|^D65$/.test(v) && v !== (options[0])) ?? options.find((v) => v !== 'D50');
  await illum.selectOption(other);
  await page.waitForFunction((b0) => document.querySelector('#step-reference .swatch[data-id="A1"]')?.textContent !== b0, before);
  const after = await page.textContent('#step-reference .swatch[data-id="A1"]');
  assert.notEqual(after, before);
  assert.match(await page.textContent('#step-reference .summary'), new RegExp(`illuminant ${other}`));
  await screenshot(page, 'reference-switched');

  const input = '#step-reference input[type=file]';
  await upload(page, input, 'cc24_Lab_D50.csv', fs.readFileSync(fixture('cc24_Lab_D50.csv')));
  await page.waitForFunction(() => /cc24_Lab_D50\.csv/.test(document.querySelector('#step-reference .summary')?.textContent ?? ''));
  assert.ok(await noErrorNear(page, input));
  assert.equal(await page.locator('#step-reference .swatch').count(), 24);
  const good = await page.textContent('#step-reference .summary');

  await upload(page, input, 'malformed_Lab.csv', fs.readFileSync(fixture('malformed_Lab.csv')));
  const err = await errorNear(page, input);
  assert.ok(err.code && err.code !== 'INTERNAL', `coded error expected, got ${JSON.stringify(err)}`);
  assert.match(err.text, /malformed_Lab\.csv/);
  // The last good reference is still shown.
  assert.equal(await page.textContent('#step-reference .summary'), good);
  await screenshot(page, 'reference-upload-error');
});

// Cancelling a long fit terminates the worker and starts a new one; the page re-sends the RAW
// bytes it keeps, so sampling, fitting and applying keep working afterwards.
import test from 'node:test';
import assert from 'node:assert/strict';
import { openPage, step } from './journey.mjs';

test('cancel stops a long fit; the restarted engine re-decodes the stored RAW and fits again', async () => {
  const b = await openPage();
  try {
    const { page } = b;
    await step(page, 'fit');
    const models = page.locator('#step-fit input[data-model]');
    for (let i = 0; i < await models.count(); i++) await models.nth(i).setChecked(true);
    const objs = page.locator('#step-fit input[data-objective]');
    for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(true);
    const gen0 = await page.evaluate(() => window.tristim.engine.generation);
    await page.click('#step-fit button.primary');
    await page.waitForFunction(() => document.querySelectorAll('#step-fit .fit-log li').length >= 1, null, { timeout: 30000 });
    await page.click('#step-fit button:has-text("Cancel")');
    await page.waitForFunction(() => /Cancelled/.test(document.querySelector('#step-fit .fit-log')?.textContent ?? ''));
    assert.equal(await page.evaluate(() => window.tristim.engine.generation), gen0 + 1);
    assert.equal(await page.isEnabled('#step-fit button.primary'), true);

    // The new worker has no decoded image: moving a corner makes the page re-send the bytes.
    await step(page, 'images');
    await page.focus('#step-images .handle[data-corner="1"]');
    await page.keyboard.press('ArrowUp');
    await page.waitForFunction(() => {
      const s = window.tristim.derived.sample, c = window.tristim.session.corners;
      return s && c && s.corners[3] === c[3];
    }, null, { timeout: 30000 });
    assert.equal(await page.locator('#step-images .patch-table tbody tr').count(), 24);

    // A short fit runs to the end on the new worker.
    await step(page, 'fit');
    for (let i = 0; i < await models.count(); i++) await models.nth(i).setChecked(i === 0);
    for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(i === 0);
    await page.click('#step-fit button.primary');
    await page.waitForSelector('#step-results:not([hidden]) table.compare', { timeout: 60000 });
    assert.equal(await page.locator('#step-results table.compare tbody tr').count(), 1);
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});

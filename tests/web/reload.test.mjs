// Reload mid-session: files, corners, settings and fitted results come back from IndexedDB;
// "New session" clears them.
import test from 'node:test';
import assert from 'node:assert/strict';
import { openPage, caps, step, waitReady } from './journey.mjs';

test('a reload restores the session; New session clears it', async (t) => {
  const b = await openPage();
  try {
    const { page } = b;
    const c = await caps(page);
    if (!c.referenceChart && !c.decodeRaw) { t.skip('engine has neither referenceChart() nor decodeRaw() yet'); return; }
    // Change a setting (illuminant) and, when images work, a corner.
    let pickIllum = null;
    if (c.referenceChart) {
      await step(page, 'reference');
      const illum = page.locator('#step-reference select').nth(1);
      const values = await illum.locator('option').evaluateAll((os) => os.map((o) => o.value));
      pickIllum = values.find((v) => v !== 'D50');  // a fresh session uses D50
      await illum.selectOption(pickIllum);
      await page.waitForFunction((v) => document.querySelector('#step-reference .summary')?.textContent.includes(`illuminant ${v}`), pickIllum);
    }
    const applied = !!(c.applyProfileToImage && await page.evaluate(() => window.tristim.session.results?.length));
    if (applied) {
      await step(page, 'apply');
      await page.click('#step-apply button.primary');
      await page.waitForSelector('#step-apply .apply-images:not([hidden])', { timeout: 60000 });
    }
    let corners = null;
    if (c.decodeRaw && c.sampleChart) {
      await step(page, 'images');
      await page.waitForSelector('#step-images .patch-table');
      await page.focus('#step-images .handle[data-corner="1"]');
      await page.keyboard.press('ArrowDown');
      await page.keyboard.press('ArrowDown');
      await page.waitForTimeout(400);
      corners = await page.evaluate(() => Array.from(window.tristim.session.corners));
    }
    const nResults = await page.evaluate(() => window.tristim.session.results?.length ?? 0);
    const summary = await page.textContent('#step-reference .summary');

    await page.reload();
    await waitReady(page);
    if (pickIllum) {
      assert.equal(await page.inputValue('#step-reference select >> nth=1'), pickIllum);
      assert.equal(await page.textContent('#step-reference .summary'), summary);
    }
    if (corners) {
      assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.views.images.editor.corners)), corners);
      await page.waitForSelector('#step-images .patch-table');
      assert.equal(await page.locator('#step-images .patch-table tbody tr').count(), 24);
    }
    assert.equal(await page.evaluate(() => window.tristim.session.results?.length ?? 0), nResults);
    if (applied) {
      // The applied image comes back when the step is visited.
      await step(page, 'apply');
      await page.waitForSelector('#step-apply .apply-images:not([hidden])', { timeout: 60000 });
      assert.match(await page.textContent('#step-apply .legend-box'), /viridis/);
    }
    if (nResults) assert.equal(await page.locator('#step-results table.compare tbody tr').count(), nResults);

    // New session: confirm, reload, defaults again.
    page.once('dialog', (d) => d.accept());
    await Promise.all([page.waitForEvent('load'), page.click('#new-session')]);
    await waitReady(page);
    if (pickIllum) assert.notEqual(await page.inputValue('#step-reference select >> nth=1'), pickIllum);
    if (corners) assert.notDeepEqual(await page.evaluate(() => Array.from(window.tristim.views.images.editor.corners)), corners);
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});

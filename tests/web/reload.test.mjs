// Reload mid-session: a known state is set up (illuminant changed, a corner moved, one fit made,
// the profile applied with a non-default colour map), kept in IndexedDB, and every part of it
// comes back after a reload; "New session" clears it and the example comes back.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repoRoot } from './harness.mjs';
import { step, waitReady, waitSampled, pageTest } from './journey.mjs';

const example = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));
const A1 = '#step-images .patch-table tbody tr[data-id="A1"]';
const ILLUM = '#step-reference select >> nth=1';

/// What IndexedDB holds under `key` (results as their model ids, settings as the illuminant).
const storedValue = (page, key) => page.evaluate(async (k) => {
  const v = await window.tristim.store.get(k);
  return k === 'results' ? v?.map((r) => r.modelId) : k === 'settings' ? v?.illuminant : v;
}, key);
/// Waits (polling the store) until it holds `expected` under `key`.
async function stored(page, key, expected, timeout = 30000) {
  const t0 = Date.now();
  let v;
  while (Date.now() - t0 < timeout) {
    v = await storedValue(page, key);
    if (JSON.stringify(v) === JSON.stringify(expected)) return;
    await new Promise((r) => setTimeout(r, 50));
  }
  assert.deepEqual(v, expected, `IndexedDB '${key}'`);
}

pageTest('a reload restores illuminant, corners, fitted results and the applied image; New session clears them', async ({ page }) => {
  // The fresh session: the example with its preset corners, D50.
  assert.equal(await page.inputValue(ILLUM), 'D50');
  assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.session.corners)), example.corners);

  // 1 Illuminant: anything but the fresh session's D50.
  await step(page, 'reference');
  const values = await page.locator(ILLUM).locator('option').evaluateAll((os) => os.map((o) => o.value));
  const illum = values.includes('D65') ? 'D65' : values.find((v) => v !== 'D50');
  assert.ok(illum, `an illuminant other than D50 is offered: ${values}`);
  await page.selectOption(ILLUM, illum);
  await page.waitForFunction((v) => document.querySelector('#step-reference .summary')?.textContent.includes(`illuminant ${v}`), illum);
  await stored(page, 'settings', illum);
  const summary = await page.textContent('#step-reference .summary');

  // 2 Corners: corner 2 (top-right) two pixels down with the keyboard.
  await step(page, 'images');
  await page.waitForSelector(A1);
  await page.focus('#step-images .handle[data-corner="1"]');
  await page.keyboard.press('ArrowDown');
  await page.keyboard.press('ArrowDown');
  const corners = [...example.corners];
  corners[3] += 2;
  await waitSampled(page, corners);
  await stored(page, 'corners', corners);
  const rowA1 = await page.textContent(A1);

  // 3 One fit: the second model the engine offers (not the example's first), first objective.
  await step(page, 'fit');
  const boxes = page.locator('#step-fit input[data-model]');
  const modelId = await boxes.nth(1).getAttribute('data-model');
  for (let i = 0; i < await boxes.count(); i++) await boxes.nth(i).setChecked(i === 1);
  const objs = page.locator('#step-fit input[data-objective]');
  for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(i === 0);
  await page.click('#step-fit button.primary');
  await page.waitForSelector('#step-results:not([hidden]) table.compare', { timeout: 120000 });
  await stored(page, 'results', [modelId]);
  const resultRow = await page.textContent('#step-results table.compare tbody tr');

  // 4 Apply with the cividis colour map.
  await step(page, 'apply');
  await page.selectOption('#step-apply select >> nth=1', 'cividis');
  await page.click('#step-apply button.primary');
  await page.waitForSelector('#step-apply .apply-images:not([hidden])', { timeout: 60000 });
  assert.match(await page.textContent('#step-apply .legend-box'), /cividis/);
  await stored(page, 'applied', true);
  await stored(page, 'colourMap', 'cividis');

  await page.reload();
  await waitReady(page);
  // Illuminant and the reference computed with it.
  assert.equal(await page.inputValue(ILLUM), illum);
  await page.waitForFunction((s) => document.querySelector('#step-reference .summary')?.textContent === s, summary);
  // Corners: on the handles, and the table sampled with them gives the same numbers.
  assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.views.images.editor.corners)), corners);
  await waitSampled(page, corners);
  assert.equal(await page.locator('#step-images .patch-table tbody tr').count(), 24);
  assert.equal(await page.textContent(A1), rowA1);
  // The one fit, and nothing else (the example is not fitted again).
  assert.deepEqual(await page.evaluate(() => window.tristim.session.results.map((r) => r.modelId)), [modelId]);
  assert.equal(await page.locator('#step-results table.compare tbody tr').count(), 1);
  assert.equal(await page.textContent('#step-results table.compare tbody tr'), resultRow);
  // The applied image comes back when the step is visited, with the colour map chosen.
  await step(page, 'apply');
  assert.equal(await page.inputValue('#step-apply select >> nth=1'), 'cividis');
  await page.waitForSelector('#step-apply .apply-images:not([hidden])', { timeout: 60000 });
  assert.match(await page.textContent('#step-apply .legend-box'), /cividis/);

  // New session: confirm, reload, the example's defaults again.
  page.once('dialog', (d) => d.accept());
  await Promise.all([page.waitForEvent('load'), page.click('#new-session')]);
  await waitReady(page);
  assert.equal(await page.inputValue(ILLUM), 'D50');
  assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.views.images.editor.corners)), example.corners);
  assert.notDeepEqual(await page.evaluate(() => window.tristim.session.results.map((r) => r.modelId)), [modelId]);
  assert.equal(await page.evaluate(() => window.tristim.session.applied), undefined);
});

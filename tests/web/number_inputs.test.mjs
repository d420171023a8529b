// Number boxes. What the browser cannot read as a number ('1e', '--': an <input type=number> then
// reports '' as its value) used to be read as an empty box, i.e. as 0 or the default, without a
// word. Now such a typo, and an empty box that needs a number, shows INVALID_ARGUMENT next to that
// box, what the box controls keeps its last good value, and a good number afterwards clears the
// message and is used; a typo typed into an empty box or a typo cleared (no change event: '' before
// and after) is read when the box is left. One box of each kind: a fit option, the custom chart
// grid, the sampled area, the light trap, Table IV's noise, the Phase I range, the absolute fit's
// noise floor and the number of principal components of the sensitivity estimate.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { step, errorNear, noErrorNear, pageTest } from './journey.mjs';

/// Types `text` into the box as a user does (Playwright refuses to fill text into type=number)
/// and commits it with Tab (a change event).
async function typeInto(page, sel, text) {
  await page.$eval(sel, (e) => { e.closest('details')?.setAttribute('open', ''); e.scrollIntoView({ block: 'center' }); });
  await page.click(sel);
  await page.keyboard.press('Control+A');
  await page.keyboard.press('Backspace');
  if (text) await page.keyboard.type(text);
  await page.keyboard.press('Tab');
}
const badInput = (page, sel) => page.$eval(sel, (e) => e.validity.badInput);
const rowCount = (page) => page.locator('#step-images .patch-table tbody tr').count();

pageTest('number boxes: a typo or a needed empty box is INVALID_ARGUMENT next to the box, the last good value is kept', async ({ page }) => {

  // a fit option (the PSM objective's expansion, 2 by default)
  await step(page, 'fit');
  const EXP = '#step-fit details[data-objective="psm"] input[data-option="expansion"]';
  await typeInto(page, EXP, '1e');
  assert.ok(await badInput(page, EXP), 'Chromium reports "1e" as bad input');
  let e = await errorNear(page, EXP);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /not a number.*keep 2/);
  await typeInto(page, EXP, '');   // the typo cleared: no change event, the box is read on leaving it
  await page.waitForFunction((sel) => /needs a number/.test(document.getElementById(document.querySelector(sel).getAttribute('aria-describedby')).textContent), EXP);
  await typeInto(page, EXP, '3');
  assert.ok(await noErrorNear(page, EXP));
  await typeInto(page, EXP, '');
  assert.match((await errorNear(page, EXP)).text, /needs a number.*keep 3/);
  await typeInto(page, EXP, '2');
  assert.ok(await noErrorNear(page, EXP));

  // the custom grid and the sampled area: the table keeps the last good sampling
  await step(page, 'images');
  assert.equal(await rowCount(page), 24);
  const ROWS = '#step-images input[data-layout="rows"]', LEFT = '#step-images input[data-layout="margin_left"]';
  const AREA = '#step-images input[data-role="sample-area"]';
  await page.selectOption('#step-images select[data-role="layout"]', 'custom');
  await page.waitForFunction(() => document.querySelectorAll('#step-images .patch-table tbody tr[data-id="R1C1"]').length === 1);
  await typeInto(page, ROWS, '');
  e = await errorNear(page, ROWS);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /Rows: needs a number/);
  await typeInto(page, LEFT, '--');
  e = await errorNear(page, LEFT);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /Margin left/);
  await typeInto(page, LEFT, '');   // cleared: empty margins are 0, so the message goes (rows still empty)
  await page.waitForFunction((sel) => document.querySelector(sel).getAttribute('aria-invalid') === null, LEFT);
  assert.match((await errorNear(page, ROWS)).text, /Rows: needs a number/);
  await typeInto(page, LEFT, '--');   // a typo into an empty box: no change event either
  assert.equal((await errorNear(page, LEFT)).code, 'INVALID_ARGUMENT');
  await typeInto(page, ROWS, '2');   // rows good now, the margin still not
  assert.ok(await noErrorNear(page, ROWS));
  assert.equal((await errorNear(page, LEFT)).code, 'INVALID_ARGUMENT');
  assert.equal(await rowCount(page), 24, 'the last good sampling (4 × 6) stays');
  await typeInto(page, LEFT, '0');
  await page.waitForFunction(() => document.querySelectorAll('#step-images .patch-table tbody tr').length === 12);
  assert.ok(await noErrorNear(page, LEFT));
  await typeInto(page, AREA, '0.5e');
  assert.equal((await errorNear(page, AREA)).code, 'INVALID_ARGUMENT');
  await typeInto(page, AREA, '0.4');
  assert.ok(await noErrorNear(page, AREA));
  await page.selectOption('#step-images select[data-role="layout"]', 'passport');
  await page.waitForFunction(() => document.querySelectorAll('#step-images .patch-table tbody tr').length === 24);
  // the light trap's boxes: a typo is named next to the trap, which stays where it was
  const TRAP = '#step-images fieldset.light-trap';
  await page.check(`${TRAP} input[type=checkbox]`);
  await page.waitForFunction(() => !!window.tristim.derived.sample?.lightTrapCorners);
  const trapBefore = await page.evaluate(() => JSON.stringify(window.tristim.derived.sample.lightTrapCorners));
  await typeInto(page, `${TRAP} input[data-trap="x"]`, '1e');
  e = await errorNear(page, `${TRAP} input[type=checkbox]`);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /Light trap x/);
  assert.equal(await page.evaluate(() => JSON.stringify(window.tristim.derived.sample.lightTrapCorners)), trapBefore);
  await page.uncheck(`${TRAP} input[type=checkbox]`);

  // Table IV's noise and the Phase I range (read when their buttons are pressed)
  await step(page, 'surface');
  const NOISE = '#step-surface input[data-role="surface-noise"]';
  await typeInto(page, NOISE, '1e');
  await page.click('#step-surface [data-role="surface-table4"]');
  e = await errorNear(page, NOISE);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /Noise σ/);
  assert.equal(await page.$$eval('#step-surface .surface-table4', (t) => t.length), 0, 'no table from a noise nobody typed');
  const FROM = '#step-surface input[data-role="surface-range-min"]';
  await typeInto(page, FROM, '');
  await page.click('#step-surface button:has-text("Use the example second measurement")');
  e = await errorNear(page, FROM);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /from λ \(nm\): needs a number/);

  // the absolute fit's noise floor and the sensitivity estimate's K
  await step(page, 'absolute');
  const FLOOR = '#step-absolute [data-role="abs-noise"]', K = '#step-absolute [data-role="abs-ssf-components"]';
  await typeInto(page, FLOOR, '--');
  await page.click('#step-absolute [data-role="abs-fit"]');
  e = await errorNear(page, FLOOR);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /Noise floor/);
  await typeInto(page, K, '4e');
  await page.click('#step-absolute [data-role="abs-ssf-estimate"]');
  e = await errorNear(page, K);
  assert.equal(e.code, 'INVALID_ARGUMENT');
  assert.match(e.text, /Principal components K/);
  await screenshot(page, 'number-inputs');
});

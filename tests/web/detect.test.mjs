// Chart detection on the page (issue 12): the example's chart is detected and drawn as a proposal
// with its patch grid and confidence; using it samples the same patches as the manual preset
// (within 1 %, or 2 standard errors where pixel noise alone is larger — the native test's rule);
// "Detect again" works; an image without a chart shows a coded message and leaves the corners.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { screenshot, repoRoot } from './harness.mjs';
import { pageTest, step, upload, fileBuffer, waitSampled } from './journey.mjs';
import { testFiles } from '../support/test_files.mjs';

const example = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));
const KDC = testFiles.kodakDc50Kdc;   // a city photo: no chart
const PANEL = '#step-images .detect-panel';
const panelState = (page, state, timeout = 60000) =>
  page.waitForFunction(([sel, s]) => document.querySelector(sel)?.dataset.state === s, [PANEL, state], { timeout });
const corners = (page) => page.evaluate(() => Array.from(window.tristim.views.images.editor.corners));
const sampled = (page) => page.evaluate(() => {
  const s = window.tristim.derived.sample;
  return s.patches.map((p) => ({ id: p.id, mean: Array.from(p.mean), std: Array.from(p.std), n: p.n }));
});

pageTest('the example chart is detected, shown with its grid and confidence, and samples like the preset', async ({ page }) => {
  await step(page, 'images');
  // A proposal: the preset corners stay in use until the user takes the detected ones.
  await panelState(page, 'proposal');
  assert.deepEqual(await corners(page), example.corners);
  const confidence = Number(await page.getAttribute(PANEL, 'data-confidence'));
  assert.ok(confidence > 0.8, `confidence ${confidence}`);
  assert.match(await page.textContent(`${PANEL} .detect-text`), /Detected: .*Passport.*confidence [01]\.\d\d, upright/);
  assert.equal(await page.locator('#step-images .overlay .detected-cell').count(), 24);
  assert.match(await page.textContent('#step-images .overlay .detect-label'), /confidence [01]\.\d\d/);
  await waitSampled(page, example.corners);
  const preset = await sampled(page);
  await screenshot(page, 'detect-1-proposal');

  // Use it: the handles move onto the detected corners, the table is sampled with them.
  await page.click(`${PANEL} button:has-text("Use the detected corners")`);
  await panelState(page, 'in-use');
  const detected = await corners(page);
  const err = Math.max(...[0, 1, 2, 3].map((k) => Math.hypot(detected[2 * k] - example.corners[2 * k], detected[2 * k + 1] - example.corners[2 * k + 1])));
  assert.ok(err < 6, `detected corners ${detected} are ${err.toFixed(2)} px from the preset`);
  await waitSampled(page, detected);
  assert.equal(await page.locator('#step-images .overlay .detected-cell').count(), 0, 'the proposal is gone once used');
  assert.equal(await page.locator('#step-images .overlay .cell').count(), 24);
  const mine = await sampled(page);
  let worst = { excess: 0, at: '' };
  preset.forEach((p, k) => [0, 1, 2].forEach((ch) => {
    const tol = Math.max(0.01 * p.mean[ch], 2 * p.std[ch] / Math.sqrt(p.n));
    const excess = Math.abs(mine[k].mean[ch] - p.mean[ch]) / tol;
    if (excess > worst.excess) worst = { excess, at: `${p.id} ${'RGB'[ch]}: preset ${p.mean[ch]}, detected ${mine[k].mean[ch]}, tolerance ${tol}` };
  }));
  assert.ok(worst.excess <= 1, worst.at);
  await screenshot(page, 'detect-2-in-use');

  // Drag a handle: the detection is marked as adjusted; "Detect again" proposes it again.
  await page.focus('#step-images .handle[data-corner="0"]');
  await page.keyboard.press('Shift+ArrowRight');
  await panelState(page, 'adjusted');
  const moved = await corners(page);
  await page.click(`${PANEL} button:has-text("Detect again")`);
  await panelState(page, 'proposal');
  assert.deepEqual(await corners(page), moved, 'a proposal does not move the handles');
  await page.click(`${PANEL} button:has-text("Use the detected corners")`);
  await panelState(page, 'in-use');
  assert.deepEqual(await corners(page), detected);
  await waitSampled(page, detected);
});

pageTest('an image without a chart: a coded message, the corners left where they were', async ({ page }) => {
  await step(page, 'images');
  await panelState(page, 'proposal');
  await upload(page, '#step-images input[data-slot="chart"]', 'city.kdc', fileBuffer(KDC));
  await panelState(page, 'none');
  const slot = await page.evaluate(() => {
    const btn = [...document.querySelectorAll('#step-images .detect-panel button')].find((x) => x.textContent === 'Detect again');
    const s = document.getElementById(btn.getAttribute('aria-describedby'));
    return { hidden: s.hidden, code: s.dataset.code, text: s.textContent };
  });
  assert.equal(slot.hidden, false);
  assert.equal(slot.code, 'CHART_NOT_FOUND');
  assert.match(await page.textContent(`${PANEL} .detect-text`), /No .* found in this image: the largest flat regions form no grid .*The corners were left where they were/);
  // A new image of another size starts from the default corners, and they stay.
  const { w, h } = await page.evaluate(() => ({ w: window.tristim.derived.image.width, h: window.tristim.derived.image.height }));
  const reset = [0.2 * w, 0.2 * h, 0.8 * w, 0.2 * h, 0.8 * w, 0.8 * h, 0.2 * w, 0.8 * h];
  assert.deepEqual(await corners(page), reset);
  await screenshot(page, 'detect-3-no-chart');
  // Corners placed by hand survive a failed "Detect again".
  const mine = reset.map((v, i) => v + (i % 2 ? 3 : -4));
  await page.evaluate((cs) => { const ed = window.tristim.views.images.editor; ed.setCorners(cs); ed.onChange(ed.corners, true); }, mine);
  await waitSampled(page, mine);
  const runs = Number(await page.getAttribute(PANEL, 'data-runs'));
  await page.click(`${PANEL} button:has-text("Detect again")`);
  await page.waitForFunction(([sel, n]) => Number(document.querySelector(sel).dataset.runs) > n, [PANEL, runs]);
  assert.equal(await page.getAttribute(PANEL, 'data-state'), 'none');
  assert.deepEqual(await corners(page), mine);
  assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.session.corners)), mine);
  assert.equal(await page.locator('#step-images .overlay .detected-cell').count(), 0);
  assert.equal(await page.isVisible('#step-images .overlay .detect-label'), false, 'no confidence label without a detected chart');
});

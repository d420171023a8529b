// Detection helped on the page (issue 48): a chart too small for the automatic passes is missed,
// the page says why and asks where the chart is; one click near it finds it (a seed point), the
// corners move onto it; a rough box dragged around it finds it too. Meanwhile the patch table,
// sampled under the corners left from before, is marked stale until the chart is found. The image is rendered at test
// time by the engine's lab (a Passport of 75 × 50 px in a 1800 × 1200 measurement image).
import test from 'node:test';
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { openPage, step, upload } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

const PANEL = '#step-images .detect-panel';
const TRUTH = [1300, 400, 1375, 400, 1375, 450, 1300, 450];
const panelState = (page, state, timeout = 60000) =>
  page.waitForFunction(([sel, s]) => document.querySelector(sel)?.dataset.state === s, [PANEL, state], { timeout });
const corners = (page) => page.evaluate(() => Array.from(window.tristim.views.images.editor.corners));
const worst = (c) => Math.max(...[0, 1, 2, 3].map((k) => Math.hypot(c[2 * k] - TRUTH[2 * k], c[2 * k + 1] - TRUTH[2 * k + 1])));
/// Page coordinates of an image point on the preview.
const onScreen = (page, x, y) => page.evaluate(([ix, iy]) => {
  const svg = document.querySelector('#step-images .overlay');
  const p = svg.createSVGPoint();
  p.x = ix; p.y = iy;
  const q = p.matrixTransform(svg.getScreenCTM());
  return [q.x, q.y];
}, [x, y]);

async function tinyPassport() {
  const T = await loadTristim();
  const out = T.labRender({ chart: 'passport', illuminant_spd: T.illuminantSpectrum('D65'), width: 1800, height: 1200, corners: TRUTH });
  return Buffer.from(out.dng);
}

test('a missed chart: the page says why; one click near it finds it, so does a rough box', async () => {
  const dng = await tinyPassport();
  const b = await openPage();
  try {
    const { page } = b;
    await step(page, 'images');
    await panelState(page, 'proposal');
    await upload(page, '#step-images input[data-slot="chart"]', 'small-chart.dng', dng);
    await panelState(page, 'none');
    const text = await page.textContent(`${PANEL} .detect-text`);
    assert.match(text, /No .*Passport.* found in this image: (no flat region is shaped like a patch|the largest flat regions form no grid)/);
    assert.match(text, /click near the chart on the image, or drag a rough box around it/);
    // The patch table still holds the samples under the corners from before: marked stale, none "ok".
    await page.waitForFunction(() => document.querySelector('#step-images .table-box')?.classList.contains('stale'));
    assert.match(await page.textContent('#step-images .summary'), /No chart found in this image/);
    const staleFlags = await page.$$eval('#step-images .patch-table td.flags', (tds) => tds.map((td) => td.textContent));
    assert.ok(staleFlags.length > 0 && staleFlags.every((f) => /stale/.test(f)), staleFlags.join(' | '));
    await screenshot(page, 'detect-help-1-missed');
    // One click a few pixels off the chart.
    const [cx, cy] = await onScreen(page, 1330, 465);
    await page.mouse.click(cx, cy);
    await panelState(page, 'in-use');
    const found = await corners(page);
    assert.ok(worst(found) < 1, `corners ${found} vs ${TRUTH}`);
    assert.match(await page.textContent(`${PANEL} .detect-text`), /Corners found automatically: .*Passport/);
    // Sampled again at the found corners: no longer stale.
    await page.waitForFunction(() => !document.querySelector('#step-images .table-box').classList.contains('stale')
      && [...document.querySelectorAll('#step-images .patch-table td.flags')].every((td) => !/stale/.test(td.textContent)));
    assert.match(await page.textContent('#step-images .summary'), /patches sampled/);
    await screenshot(page, 'detect-help-2-found');
    // The help is disarmed once found: a click on the image moves nothing.
    await page.mouse.click(...(await onScreen(page, 300, 300)));
    assert.deepEqual(await corners(page), found);
    // "Detect again" misses again (the whole image); a rough box dragged around the chart finds it.
    await page.evaluate(() => { const ed = window.tristim.views.images.editor; ed.setCorners([200, 200, 600, 200, 600, 500, 200, 500]); ed.onChange(ed.corners, true); });
    const runs = Number(await page.getAttribute(PANEL, 'data-runs'));
    await page.click(`${PANEL} button:has-text("Detect again")`);
    await page.waitForFunction(([sel, n]) => Number(document.querySelector(sel).dataset.runs) > n, [PANEL, runs]);
    assert.equal(await page.getAttribute(PANEL, 'data-state'), 'none');
    const [x0, y0] = await onScreen(page, 1270, 380);
    const [x1, y1] = await onScreen(page, 1400, 470);
    await page.mouse.move(x0, y0);
    await page.mouse.down();
    await page.mouse.move((x0 + x1) / 2, (y0 + y1) / 2, { steps: 4 });
    await page.mouse.move(x1, y1, { steps: 4 });
    await page.mouse.up();
    await panelState(page, 'in-use');
    assert.ok(worst(await corners(page)) < 1);
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});

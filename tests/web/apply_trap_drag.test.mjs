// Step 5, the scene's light trap drawn on the image (Abed 2013 App. C step 8): the four handles of
// the corner editor (web/images/corners.js) dragged onto a region of the scene fill the typed
// corners field; the applied XYZ equal `tristim apply … --light-trap <those corners>` to the bit;
// typing corners moves the handles to exactly the typed numbers. The scene's flat (itself, radial)
// is set too, so the trap is measured after a flat; a trap alone: apply_trap_only.test.mjs.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, CLI, DNG, artifact, filePath } from './journey.mjs';
import { readPfm, samePixels, chooseScene, applyScene } from './apply_pfm.mjs';

const TARGET = [605, 445, 641, 447, 640, 480, 606, 478];   // image pixels: a quad inside the Passport's black patch D6
const EDITOR = '#step-apply .trap-editor';

/// Screen position of image point (x, y) of the trap editor.
const screenOf = (page, x, y) => page.evaluate(([px, py, sel]) => {
  const svg = document.querySelector(`${sel} svg.overlay`);
  const p = svg.createSVGPoint(); p.x = px; p.y = py;
  const q = p.matrixTransform(svg.getScreenCTM());
  return [q.x, q.y];
}, [x, y, EDITOR]);
const editorCorners = (page) => page.evaluate((sel) => [...document.querySelectorAll(`${sel} .handle`)]
  .flatMap((g) => g.getAttribute('transform').match(/translate\(([^,]+),([^)]+)\)/).slice(1).map(Number)), EDITOR);

pageTest('apply: the light trap dragged on the scene equals tristim apply --light-trap with the same corners', { timeout: 600000 }, async ({ page }) => {
  const dng = filePath(DNG);
  await chooseScene(page, dng, { flat: dng, flatMode: 'radial' });
  // The scene decodes when chosen: its preview appears under the four handles.
  await page.waitForSelector('#step-apply .trap-draw:not([hidden])', { timeout: 120000 });
  await page.locator(EDITOR).scrollIntoViewIfNeeded();
  assert.equal(await page.inputValue('#step-apply input[data-frame="light-trap"]'), '', 'no trap until a handle moves');

  // 1. Drag each handle onto its target corner.
  for (let i = 0; i < 4; i++) {
    const box = await page.locator(`${EDITOR} .handle`).nth(i).locator('circle.dot').boundingBox();
    const to = await screenOf(page, TARGET[2 * i], TARGET[2 * i + 1]);
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(...to, { steps: 5 });
    await page.mouse.up();
  }
  const typed = await page.inputValue('#step-apply input[data-frame="light-trap"]');
  const dragged = typed.split(',').map(Number);
  assert.equal(dragged.length, 8, `the field holds the dragged corners: '${typed}'`);
  for (let k = 0; k < 8; k++) assert.ok(Math.abs(dragged[k] - TARGET[k]) < 3, `dragged ${dragged} ≈ ${TARGET}`);
  assert.deepEqual(await editorCorners(page), dragged, 'handles and field agree');

  // 2. Applied with the dragged trap: the CLI with the field's corners gives the same XYZ, to the bit.
  const { profile } = await applyScene(page, /light trap: flare R /, 'apply-trap-drag');
  await screenshot(page, 'apply-trap-drag');
  const out = artifact('apply-trap-drag.pfm');
  execFileSync(CLI, ['apply', profile, dng, '--flat', dng, '--flat-mode', 'radial', '--light-trap', typed, '--out', out], { stdio: 'ignore' });
  const pfm = readPfm(fs.readFileSync(out));
  await samePixels(page, pfm, [[0, 0], [620, 460], [300, 200], [500, 400], [pfm.width - 1, pfm.height - 1]]);

  // 3. The typed path: corners typed move the handles to exactly those numbers.
  await page.fill('#step-apply input[data-frame="light-trap"]', TARGET.join(','));
  assert.deepEqual(await editorCorners(page), TARGET);
  // and "No light trap" empties the field (the handles stay, dimmed).
  await page.click('#step-apply .trap-draw button');
  assert.equal(await page.inputValue('#step-apply input[data-frame="light-trap"]'), '');
});

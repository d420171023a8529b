// Step 5 on another RAW with its own frames (Abed 2013 App. C step 8): a flat field and a light trap
// typed as corners (dark frames: apply_dark.test.mjs); the page's applied XYZ equal `tristim apply …
// --flat … --light-trap …` (float32 PFM) at sampled pixels, to the bit, and are not all zero.
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, CLI, DNG, artifact, filePath } from './journey.mjs';
import { readPfm, samePixels, chooseScene, applyScene } from './apply_pfm.mjs';

pageTest('apply with the scene\'s own flat field and light trap equals tristim apply', { timeout: 600000 }, async ({ page }) => {
  // The same RAW as its flat field, fitted as a radial fall-off (Guarnera 2018 eq 7; a per-pixel
  // flat needs signal in every pixel, which a chart photo lacks), and a light trap typed as corners.
  const dng = filePath(DNG);
  await chooseScene(page, dng, { flat: dng, flatMode: 'radial' });
  const trap = '20,20,80,20,80,60,20,60';
  await page.fill('#step-apply input[data-frame="light-trap"]', trap);
  const { profile } = await applyScene(page, /flat field \(radial\); light trap: flare/, 'apply-frames');
  const out = artifact('apply-frames.pfm');
  execFileSync(CLI, ['apply', profile, dng, '--flat', dng, '--flat-mode', 'radial', '--light-trap', trap, '--out', out], { stdio: 'ignore' });
  const pfm = readPfm(fs.readFileSync(out));
  await samePixels(page, pfm, [[0, 0], [300, 200], [500, 400], [pfm.width - 1, pfm.height - 1], [123, 77]]);
  await screenshot(page, 'apply-frames');
});

// Step 5 on a scene with its own dark frames (Abed 2013 App. C step 8). No RAW dark/bright pair of
// one camera is in the repository, so the engine's lab renderer makes one: a chart scene and two
// dark frames of the same camera and size (`tristim lab render … --exposure 1e-6`: near zero light,
// read noise 3 DN, other seeds). The page's applied XYZ with both dark frames (averaged, per pixel)
// equal `tristim apply … --dark d1 --dark d2` to the bit, and differ from the scene without them.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, CLI, artifact } from './journey.mjs';
import { readPfm, samePixels, chooseScene, applyScene } from './apply_pfm.mjs';

/// A rendered DNG of one camera and size (600×400 measurement pixels) in test-artifacts/.
function render(name, exposure, seed) {
  const out = artifact(`apply-dark-${name}.dng`);
  execFileSync(CLI, ['lab', 'render', '--camera', 'Canon_EOS_5D_Mark_II', '--chart', 'passport', '--illuminant', 'D65',
    '--exposure', String(exposure), '--noise', '0.5,3', '--seed', String(seed), '--size', '600x400', '--out', out], { stdio: 'ignore' });
  return out;
}

pageTest('apply with the scene\'s own dark frames equals tristim apply --dark', { timeout: 600000 }, async ({ page }) => {
  const scene = render('scene', 0.5, 1), darks = [render('dark1', 1e-6, 2), render('dark2', 1e-6, 3)];
  await chooseScene(page, scene);
  await page.setInputFiles('#step-apply input[data-frame="dark"]', darks);
  const { profile } = await applyScene(page, /dark: 2 frame\(s\) averaged/, 'apply-dark');
  assert.match(await page.textContent('#step-apply p.summary:not(.frames-note)'), /Applied to 600×400/);
  await screenshot(page, 'apply-dark');
  const run = (out, ...frames) => { execFileSync(CLI, ['apply', profile, scene, ...frames, '--out', out], { stdio: 'ignore' }); return readPfm(fs.readFileSync(out)); };
  const withDark = run(artifact('apply-dark.pfm'), '--dark', darks[0], '--dark', darks[1]);
  const without = run(artifact('apply-dark-none.pfm'));
  const points = [[0, 0], [123, 77], [300, 200], [450, 300], [599, 399]];
  await samePixels(page, withDark, points);
  // The dark frames did something: at these pixels the scene without them differs.
  assert.ok(points.some(([x, y]) => withDark.at(x, y).some((v, c) => v !== without.at(x, y)[c])), 'dark subtraction changes the applied XYZ');
});

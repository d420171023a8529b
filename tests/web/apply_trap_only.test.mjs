// Step 5 with ONLY a light trap (Abed 2013 App. C steps 1 and 8): no dark frame, no flat. The
// applied XYZ equal `tristim apply … --light-trap <corners>` to the bit and differ from the same
// profile applied with no trap (the flare is subtracted, not skipped).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, CLI, DNG, artifact, filePath } from './journey.mjs';
import { readPfm, samePixels, chooseScene, applyScene } from './apply_pfm.mjs';

const TRAP = '605,445,641,447,640,480,606,478';   // image pixels: a quad inside the Passport's black patch D6
const POINTS = [[0, 0], [620, 460], [300, 200], [500, 400]];

pageTest('apply: a light trap alone equals tristim apply --light-trap, and differs from no trap', { timeout: 600000 }, async ({ page }) => {
  const dng = filePath(DNG);
  await chooseScene(page, dng);
  await page.waitForSelector('#step-apply .trap-draw:not([hidden])', { timeout: 120000 });
  await page.fill('#step-apply input[data-frame="light-trap"]', TRAP);
  const { profile } = await applyScene(page, /light trap: flare R /, 'apply-trap-only');
  await screenshot(page, 'apply-trap-only');

  const cli = (name, extra) => {
    const out = artifact(name);
    execFileSync(CLI, ['apply', profile, dng, ...extra, '--out', out], { stdio: 'ignore' });
    return readPfm(fs.readFileSync(out));
  };
  const trapped = cli('apply-trap-only.pfm', ['--light-trap', TRAP]);
  await samePixels(page, trapped, [...POINTS, [trapped.width - 1, trapped.height - 1]]);

  const plain = cli('apply-trap-none.pfm', []);
  const differs = [];
  for (const [x, y] of POINTS) {
    const p = await page.evaluate(([px, py]) => window.tristim.engine.call('pixel', { x: px, y: py }), [x, y]);
    if (p.XYZ.some((v, c) => v !== plain.at(x, y)[c])) differs.push([x, y]);
  }
  assert.deepEqual(differs, POINTS, 'every compared pixel differs from the profile applied without the trap');
});

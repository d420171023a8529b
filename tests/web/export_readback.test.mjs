// Export step: a .cube or ICC file loaded back is described by the engine's readers
// (tristim/profile/headers.hpp, through the worker), and a malformed one is refused next to the
// file input with the engine's code. Screenshot: test-artifacts/export-readback.png.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { screenshot, repoRoot } from './harness.mjs';
import { step, upload, errorFor, pageTest } from './journey.mjs';

const INPUT = '#step-export input[type=file]';
const resultText = (page) => page.locator('#step-export .import-result').textContent();

pageTest('export step: .cube and ICC files read back by the engine; a short .cube refused, coded', async ({ page }) => {
  await step(page, 'export');
  const icc = fs.readFileSync(path.join(repoRoot, 'tests/fuzz/corpus/icc/matrix-3x3.icc'));
  await upload(page, INPUT, 'matrix.icc', icc);
  await page.waitForFunction(() => /ICC v4/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''));
  const iccText = await resultText(page);
  assert.match(iccText, /matrix\.icc: ICC v4\.\d scnr profile/);
  assert.match(iccText, new RegExp(`RGB → (XYZ|Lab), ${icc.length} bytes, tags .*rXYZ`));
  const cube = fs.readFileSync(path.join(repoRoot, 'tests/fuzz/corpus/cube/shaper.cube'));
  await upload(page, INPUT, 'shaper.cube', cube);
  await page.waitForFunction(() => /3D LUT/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''));
  assert.match(await resultText(page), /shaper\.cube: a 2×2×2 3D LUT after a 2-row 1D shaper, domain 0 0 0 … 1 1 1\./);
  await screenshot(page, 'export-readback');
  await upload(page, INPUT, 'short.cube', Buffer.from('LUT_3D_SIZE 2\n0 0 0\n'));
  const err = await errorFor(page, INPUT, 'short.cube');
  assert.equal(err.code, 'PARSE_ERROR');
  assert.match(err.text, /1 table rows, expected 2³ = 8/);
});

// The Export step's dual-illuminant DCP (issue 46): with a second profile of the camera loaded (the
// example's profile relabelled as calibrated under illuminant A and loaded back), the DCP names both
// calibration illuminants, its bytes are the CLI's `tristim export --profile … --second … --dcp`,
// and two profiles under the same illuminant give SAME_ILLUMINANT beside the button.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { step, pageTest, CLI, artifact } from './journey.mjs';

pageTest('export step: dual-illuminant DCP from two loaded profiles, byte-identical to `tristim export --second`', { problems: false }, async ({ page }) => {
  await step(page, 'export');
  const model = await page.inputValue('#dcp-camera-model');
  // The selected profile (what "Profile JSON" downloads).
  const firstKey = await page.evaluate(() => window.tristim.session.selected ?? window.tristim.session.results[0].key);
  const [dlJson] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="Profile JSON"]')]);
  const first = artifact('export-dcp-dual-D50.json');
  await dlJson.saveAs(first);

  // Same illuminant twice: the profile loaded back unchanged is refused.
  await page.setInputFiles('#step-export input[type=file]', first);
  await page.waitForSelector('#step-export [data-imported]');
  await page.selectOption('#dcp-second', { index: 1 });
  await page.click('#step-export button[data-export="DCP"]');
  await page.waitForFunction(() => /SAME_ILLUMINANT/.test(document.querySelector('#export-DCP-error')?.textContent ?? ''), null, { timeout: 30000 });

  // The second profile under A (its recipe's reference illuminant, which names a profile's).
  const json = JSON.parse(fs.readFileSync(first, 'utf8'));
  json.recipe.reference.illuminant = 'A';
  const second = artifact('export-dcp-dual-A.json');
  fs.writeFileSync(second, JSON.stringify(json));
  await page.setInputFiles('#step-export input[type=file]', second);
  await page.waitForFunction(() => /export-dcp-dual-A[.]json: profile loaded/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''), null, { timeout: 30000 });
  // The loaded profile is selected; the second is the example's own.
  await page.selectOption('#dcp-second', firstKey);
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="DCP"]')]);
  const bytes = fs.readFileSync(await dl.path());
  await page.waitForFunction(() => /CalibrationIlluminant2/.test(document.querySelector('#step-export .dcp-summary')?.textContent ?? ''), null, { timeout: 30000 });
  const summary = await page.textContent('#step-export .dcp-summary');
  assert.match(summary, /CalibrationIlluminant1 17 \(Standard Light A, 2850 K\)/);
  assert.match(summary, /CalibrationIlluminant2 23 \(D50, 5000 K\)/);
  assert.match(summary, /ForwardMatrix2/);
  await screenshot(page, 'export-dcp-dual');

  const cli = artifact('export-dcp-dual-cli.dcp');
  execFileSync(CLI, ['export', '--profile', second, '--second', first, '--dcp', cli, '--camera-model', model]);
  assert.ok(bytes.equals(fs.readFileSync(cli)), 'page dual DCP = CLI dual DCP, byte for byte');
});

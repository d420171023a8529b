// The Export step's DNG camera profile (issue 46): from the example (the first screen, fitted),
// the camera model comes from the decoded RAW, the download is named as RawTherapee looks for it,
// its bytes are the CLI's for the same profile JSON and camera model, and the engine's reader
// summarises it on the page.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { step, DNG, pageTest, CLI, artifact } from './journey.mjs';

pageTest('export step: DCP of the selected profile, byte-identical to `tristim export --dcp`, read back and summarised', { problems: false }, async ({ page }) => {
  await step(page, 'export');
  // The camera model as the RAW names it (make + model), shown and editable.
  const meta = await page.evaluate(() => window.tristim.derived.image?.metadata ?? {});
  const model = [meta.make, meta.model].filter(Boolean).join(' ');
  assert.ok(model.length > 3, `the example RAW names its camera: '${model}'`);
  assert.equal(await page.inputValue('#dcp-camera-model'), model);
  assert.equal(await page.isEditable('#dcp-camera-model'), true);
  // The file name RawTherapee needs, said on the page.
  assert.ok((await page.textContent('#step-export .dcp-file-name')).includes(`"${model}.dcp"`));
  assert.match(await page.textContent('#step-export .dcp-file-name'), /dcpprofiles/);

  // The page's profile JSON, for the CLI.
  const [dlJson] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="Profile JSON"]')]);
  const profile = artifact('export-dcp-profile.json');
  await dlJson.saveAs(profile);

  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="DCP"]')]);
  assert.equal(dl.suggestedFilename(), `${model}.dcp`);
  const bytes = fs.readFileSync(await dl.path());
  assert.equal(bytes.subarray(0, 4).toString('latin1'), 'IIRC');
  // The engine's reader on the downloaded bytes: camera, illuminant, ForwardMatrix.
  await page.waitForFunction(() => /ForwardMatrix1/.test(document.querySelector('#step-export .dcp-summary')?.textContent ?? ''), null, { timeout: 30000 });
  const summary = await page.textContent('#step-export .dcp-summary');
  assert.ok(summary.includes(`UniqueCameraModel “${model}”`), summary);
  assert.match(summary, /CalibrationIlluminant1 \d+ \([^)]+ K\)/);
  assert.match(summary, /ForwardMatrix1 (-?\d+\.\d{4} ?){3}( \/ (-?\d+\.\d{4} ?){3}){2}/);
  assert.match(summary, new RegExp(`${bytes.length} bytes`));
  await screenshot(page, 'export-dcp');

  // The CLI on the page's profile JSON writes the same bytes: with the camera model as typed,
  // and with --raw on the example DNG (the same make + model rule).
  const cli = artifact('export-dcp-cli.dcp');
  execFileSync(CLI, ['export', '--profile', profile, '--dcp', cli, '--camera-model', model]);
  assert.ok(bytes.equals(fs.readFileSync(cli)), 'page DCP = CLI DCP (--camera-model), byte for byte');
  execFileSync(CLI, ['export', '--profile', profile, '--dcp', cli, '--raw', DNG]);
  assert.ok(bytes.equals(fs.readFileSync(cli)), 'page DCP = CLI DCP (--raw), byte for byte');

  // A non-linear model's HueSatMap: select one and export again (the CLI's --hue-sat-map 90,30,30).
  // The degree-2 root-polynomial by least squares (the CLI's own DCP test fits the same model):
  // some other fits of the example map no positive camera RGB to the white (degree 4 does not),
  // and a DCP needs that camera neutral (the page then shows the engine's PROFILE_INVALID).
  const key = await page.evaluate(() => window.tristim.session.results.find((r) => r.modelId === 'Finlayson2015-2' && r.objective === 'ls')?.key);
  assert.ok(key, 'the example has a Finlayson2015-2 least-squares fit');
  await page.evaluate(async (k) => { await window.tristim.save('selected', k); window.tristim.emit('results', window.tristim.session.results); }, key);
  await page.waitForFunction(() => document.getElementById('dcp-hue-sat-map')?.disabled === false);
  await page.check('#dcp-hue-sat-map');
  const [dlJson2] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="Profile JSON"]')]);
  const profile2 = artifact('export-dcp-profile-nonlinear.json');
  await dlJson2.saveAs(profile2);
  const [dl2] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="DCP"]')]).catch(async (e) => {
    throw new Error(`${e.message}; ${key}: ${await page.textContent('#export-DCP-error')}`);
  });
  const bytes2 = fs.readFileSync(await dl2.path());
  await page.waitForFunction(() => /HueSatMap 90×30×30/.test(document.querySelector('#step-export .dcp-summary')?.textContent ?? ''), null, { timeout: 30000 });
  execFileSync(CLI, ['export', '--profile', profile2, '--dcp', cli, '--camera-model', model, '--hue-sat-map', '90,30,30']);
  assert.ok(bytes2.equals(fs.readFileSync(cli)), 'page DCP with HueSatMap = CLI DCP, byte for byte');
});

// The second chart image's own dark frames, flat field and reference file (issue 48; Abed 2013
// App. C steps 1-2 per image, docs/multi-image.md): the page subtracts and divides the frames in
// the worker before sampling the second image and pairs it with its own reference file (a CSV of
// the chart's XYZ); the profile's recipe records them in that image's capture and reference stages,
// and `tristim fit --recipe r.json --raw a.dng --raw b.dng --dark d1 --dark d2 --flat f --xyz rb.csv`
// gives the page's coefficients to the bit (and other ones without the frames); every Results
// swatch has a colour. The second chart, its dark frames and its flat (a white grid over the whole
// frame) are rendered by `tristim lab render` at test time, with fall-off and noise.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, upload, fitMatrix3x3, CLI, artifact, DNG } from './journey.mjs';
import { cliFit, greySwatches } from './several_charts_common.mjs';

const PANEL = '#step-images fieldset.second-chart';

/// {chart, darks: [d1, d2], flat}: the files' paths.
function renderFiles() {
  const render = (args, name) => {
    const out = artifact(name);
    execFileSync(CLI, ['lab', 'render', '--camera', 'Canon_EOS_5D_Mark_II', '--illuminant', 'D65', '--size', '600x400', ...args, '--out', out], { stdio: 'pipe' });
    return out;
  };
  const waves = Array.from({ length: 41 }, (_, i) => 380 + 10 * i);
  const reference = artifact('frames-b-reference.csv');
  fs.writeFileSync(reference, execFileSync(CLI, ['reference', '--chart', 'cc24', '--illuminant', 'D65']));
  const white = artifact('frames-white.csv');
  fs.writeFileSync(white, `id,${waves.join(',')}\n${['W1', 'W2', 'W3'].map((id) => `${id},${waves.map(() => '0.9').join(',')}`).join('\n')}\n`);
  return {
    reference,
    chart: render(['--chart', 'cc24', '--falloff', '0.3', '--noise', '0.5,3', '--seed', '1'], 'frames-b.dng'),
    darks: [2, 3].map((seed) => render(['--chart', 'cc24', '--exposure', '1e-6', '--noise', '0.5,3', '--seed', String(seed)], `frames-b-dark${seed}.dng`)),
    flat: render(['--reflectances', white, '--corners', '0,0,600,0,600,400,0,400', '--falloff', '0.3'], 'frames-b-flat.dng'),
  };
}

const framesShown = (page, frames) => page.waitForFunction(([sel, f]) => {
  const p = document.querySelector(sel);
  return p?.dataset.state === 'sampled' && p.dataset.frames === f;
}, [PANEL, frames], { timeout: 60000 });

pageTest('the second image\'s own dark frames, flat field and reference file: equal to tristim fit --recipe --raw a --raw b --dark --dark --flat --xyz', { timeout: 240000 }, async ({ page }) => {
  const files = renderFiles();
  await step(page, 'images');
  await page.selectOption(`${PANEL} select[data-role="chart2-chart"]`, 'cc24');
  await upload(page, `${PANEL} input[data-slot="chart2"]`, 'b.dng', fs.readFileSync(files.chart));
  await framesShown(page, '');
  const plain = await page.evaluate(() => Array.from(window.tristim.derived.sample2.patches[0].mean));
  await page.setInputFiles(`${PANEL} input[data-slot="dark2"]`, files.darks);
  await framesShown(page, 'dark2');
  await page.setInputFiles(`${PANEL} input[data-slot="flat2"]`, files.flat);
  await framesShown(page, 'dark2 flat2');
  const calibrated = await page.evaluate(() => Array.from(window.tristim.derived.sample2.patches[0].mean));
  assert.notDeepEqual(calibrated, plain, 'the frames change the second image\'s patches');
  await page.setInputFiles(`${PANEL} input[data-role="chart2-reference"]`, files.reference);
  await page.waitForFunction((sel) => /frames-b-reference\.csv: 24 patches/.test(document.querySelector(sel)?.textContent), `${PANEL} .second-frames`, { timeout: 30000 });
  await screenshot(page, 'several-charts-frames');

  await fitMatrix3x3(page);
  const profile = await page.evaluate(() => {
    const t = window.tristim;
    return JSON.parse(t.session.results.find((x) => x.key === t.session.selected).fit.profile);
  });
  const capture = profile.recipe.images[1].capture;
  assert.equal(capture.dark_frames, 2);
  assert.equal(capture.flat_field, true);
  assert.equal(profile.recipe.images[0].capture.dark_frames, 0, 'the first image has none');
  assert.equal(profile.recipe.images[1].reference.chart, 'file');
  assert.match(profile.recipe.images[1].reference.data_digest, /^fnv1a64:/);
  const grey = await greySwatches(page);
  assert.deepEqual(grey, [], 'the second chart (a ColorChecker beside the Passport): its swatches in colour');

  const fit = (recipe, extra, name) => cliFit(recipe, ['--raw', DNG, '--raw', files.chart, ...extra, '--xyz', files.reference], name).model.coefficients;
  const frames = ['--dark', files.darks[0], '--dark', files.darks[1], '--flat', files.flat];
  assert.deepEqual(fit(profile.recipe, frames, 'frames-recipe'), profile.model.coefficients, 'the page fits what the CLI fits, to the bit');
  const bare = structuredClone(profile.recipe);
  delete bare.images[1].capture;
  assert.notDeepEqual(fit(bare, [], 'frames-recipe-bare'), profile.model.coefficients, 'without the frames: another fit');
});

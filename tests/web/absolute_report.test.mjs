// Journey: the Absolute mode's report is the engine's — the one `tristim absolute evaluate --json`
// prints — to the bit. (1) The example: the page fits the virtual camera's bracket and measures its
// test scene (the cells as region rows, white patch D1 per eq 16); the CLI fits the same example
// written as files (tests/cli/absolute_fixture.cpp: DNGs named as the page names the frames, the
// page's recipe) and evaluates it. (2) Files a user uploads: a bracket of the training chart, a
// stimuli CSV of region rows naming its files, lens-cap frames, a flat and a test scene of region
// rows; the CLI fits and evaluates the same files. The downloaded report equals the CLI's JSON, and
// the figures shown are the CLI's numbers.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { screenshot } from './harness.mjs';
import { step, pageTest } from './journey.mjs';
import { absoluteFixture } from '../support/absolute_fixture.mjs';

const S = '#step-absolute';
const { dir: fixture, cli } = absoluteFixture('tristim-absolute-page-');

async function downloadReport(page) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(`${S} [data-role="abs-download-report"]`)]);
  assert.match(dl.suggestedFilename(), /-report\.json$/);
  return JSON.parse(fs.readFileSync(await dl.path(), 'utf8'));
}

/// The relative Y error of each column of the figures table, as shown, against the report's.
async function shownFigures(page, report) {
  const shown = await page.$$eval(`${S} .abs-figures-table [data-col="relY"]`, (e) => e.map((x) => x.textContent));
  const expected = [report.training.figures, ...report.test.figures.map((f) => f.metrics)].map((m) => `${(100 * m.relative_Y_error).toFixed(2)} %`);
  assert.deepEqual(shown, expected);
  const groups = await page.$$eval(`${S} .abs-figures-table thead th[data-group]`, (e) => e.map((x) => x.dataset.group));
  assert.deepEqual(groups, ['training', ...report.test.figures.map((f) => f.group)]);
  const rows = await page.$$eval(`${S} [data-role="abs-rows"] tbody tr`, (e) => e.map((x) => x.dataset.id));
  assert.deepEqual(rows, [...report.test.points, ...report.test.regions].map((r) => r.id));
}

pageTest('absolute report: the example — the page\'s report equals `tristim absolute evaluate --json` to the bit', async ({ page }) => {
  const ex = path.join(fixture(), 'example');
  cli(ex, ['absolute', 'fit', '--recipe', 'recipe.json', '--out', 'profile.json']);
  const exposures = fs.readFileSync(path.join(ex, 'exposures.txt'), 'utf8').trim().split('\n').flatMap((e) => ['--exposure', e]);
  const raws = [1, 2, 3, 4, 5].map((i) => `virtual-${i}.raw`);
  const expected = JSON.parse(cli(ex, ['absolute', 'evaluate', 'profile.json', '--stimuli', 'test.csv', ...raws, ...exposures, '--white', 'D1', '--json']));
  await step(page, 'absolute');
  await page.click(`${S} [data-role="abs-example"]`);
  await page.waitForSelector(`${S} .abs-maps:not([hidden])`, { timeout: 180000 });
  assert.equal(await page.$eval(`${S} [data-role="abs-white"]`, (e) => e.value), 'D1');
  const report = await downloadReport(page);
  assert.deepStrictEqual(report, expected);
  await shownFigures(page, report);
  // the recipe the page downloads is the one the CLI fitted the same profile from
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(`${S} [data-role="abs-download-recipe"]`)]);
  assert.equal(fs.readFileSync(await dl.path(), 'utf8'), fs.readFileSync(path.join(ex, 'recipe.json'), 'utf8'));
});

pageTest('absolute report: uploaded region rows naming the bracket\'s files — the page\'s report equals the CLI\'s to the bit', async ({ page }) => {
  const d = fixture();
  const trains = [1, 2, 3, 4, 5].map((i) => `train_${i}.dng`);
  cli(d, ['absolute', 'fit', '--stimuli', 'stimuli.csv', '--dark', 'cap_1.dng', '--dark', 'cap_2.dng', '--flat', 'flat.dng',
    '--camera', 'Canon_EOS_5D_Mark_II', ...trains.flatMap((t) => ['--bracket', t]), '--out', 'page43.json']);
  const expected = JSON.parse(cli(d, ['absolute', 'evaluate', 'page43.json', '--stimuli', 'train_test.csv', ...trains, '--json']));
  await step(page, 'absolute');
  await page.setInputFiles(`${S} [data-role="abs-series"]`, trains.map((t) => path.join(d, t)));
  await page.waitForFunction((s) => document.querySelectorAll(`${s} .abs-series tbody tr`).length === 5, S, { timeout: 60000 });
  await page.setInputFiles(`${S} [data-role="abs-stimuli"]`, path.join(d, 'stimuli.csv'));
  await page.waitForFunction((s) => /stimuli\.csv: 179 stimuli .*179 of them regions/.test(document.querySelector(`${s} [data-role="abs-stimuli-info"]`)?.textContent ?? ''), S);
  await page.setInputFiles(`${S} [data-role="abs-lenscap"]`, ['cap_1.dng', 'cap_2.dng'].map((c) => path.join(d, c)));
  await page.setInputFiles(`${S} [data-role="abs-flat"]`, path.join(d, 'flat.dng'));
  await page.setInputFiles(`${S} [data-role="abs-test"]`, path.join(d, 'train_test.csv'));
  await page.waitForFunction((s) => /train_test\.csv: 55 stimuli/.test(document.querySelector(`${s} [data-role="abs-test-info"]`)?.textContent ?? ''), S);
  await page.waitForFunction((s) => [...document.querySelectorAll(`${s} .file-state`)].filter((e) => /frame/.test(e.textContent)).length === 2, S, { timeout: 60000 });
  await page.selectOption(`${S} [data-role="abs-camera"]`, 'Canon_EOS_5D_Mark_II');
  await page.click(`${S} [data-role="abs-fit"]`);
  await page.waitForSelector(`${S} .abs-maps:not([hidden])`, { timeout: 180000 });
  const report = await downloadReport(page);
  assert.deepStrictEqual(report, expected);
  await shownFigures(page, report);
  assert.equal(report.test.regions.length, 55);
  await page.click(`${S} [data-role="abs-rows"] > summary`);
  await screenshot(page, 'absolute-report-uploaded');
});

// The results step's "Uncertainty (bootstrap)" on the example: progress while it runs, a Cancel
// that stops it, and for N = 200 the same intervals, to the bit, as `tristim fit --bootstrap` on
// the same training set (with the sampled RAW's per-patch σ and pixel count: pixels resampled) and recipe; the intervals in the table and the ellipses on the xy and a*b*
// plots.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot, openBrowser } from './harness.mjs';
import { pageTest, step, CLI, artifact, waitReady } from './journey.mjs';

/// The page after the first visit's compare of every model (slow on a busy machine).
async function open() {
  const b = await openBrowser();
  await b.page.goto(b.origin + '/');
  await waitReady(b.page, 300000);
  return b;
}

/// Fits only `model` × `objective` in step 3 and waits for its row in the results.
async function fitOne(page, model = 'matrix-3x3', objective = 'ls') {
  await step(page, 'fit');
  await page.waitForSelector('#step-fit button.primary:not([disabled])', { timeout: 180000 });
  await page.$$eval('#step-fit input[data-model], #step-fit input[data-objective]', (els, [m, o]) => {
    for (const e of els) {
      const want = e.dataset.model ? e.dataset.model === m : e.dataset.objective === o;
      if (e.checked !== want) e.click();
    }
  }, [model, objective]);
  await page.click('#step-fit button.primary');
  await page.waitForFunction(() => window.tristim.session.results?.length === 1 && !document.querySelector('#step-fit button.primary[disabled]'), null, { timeout: 120000 });
  await step(page, 'results');
}

/// The selected result's training set as CSVs and its recipe as JSON in test-artifacts/ (values in
/// JS's shortest round-trip form, so the CLI reads the same doubles).
/// With the sampled image's pixel statistics (r.std, r.n), the RGB CSV carries them as `tristim
/// sample` writes them (R_std, G_std, B_std, n), so the CLI resamples the pixels too.
function writeTraining(r) {
  const row = (id, i, a) => `${id},${a[3 * i]},${a[3 * i + 1]},${a[3 * i + 2]}`;
  const px = (i) => (r.std ? `,${r.std[3 * i]},${r.std[3 * i + 1]},${r.std[3 * i + 2]},${r.n[i]}` : '');
  fs.writeFileSync(artifact('bootstrap-rgb.csv'), `patch,R,G,B${r.std ? ',R_std,G_std,B_std,n' : ''}\n${r.ids.map((id, i) => row(id, i, r.rgb) + px(i)).join('\n')}\n`);
  fs.writeFileSync(artifact('bootstrap-xyz.csv'), `patch,X,Y,Z\n${r.ids.map((id, i) => row(id, i, r.xyz)).join('\n')}\n`);
  fs.writeFileSync(artifact('bootstrap-recipe.json'), JSON.stringify(JSON.parse(r.profile).recipe));
}
/// The selected result's training set, with the sampled image's σ and pixel count of its patches.
const training = (page) => page.evaluate(() => {
  const x = window.tristim.session.results[0], s = window.tristim.derived.sample;
  const at = (id) => s.ids.indexOf(id);
  return { ids: Array.from(x.ids), rgb: Array.from(x.rgb), xyz: Array.from(x.xyz), profile: x.fit.profile, bootstrap: x.bootstrap,
    std: Array.from(x.ids).flatMap((id) => [0, 1, 2].map((k) => s.std[3 * at(id) + k])), n: Array.from(x.ids).map((id) => s.n[at(id)]),
    sampledRGB: Array.from(x.ids).flatMap((id) => [0, 1, 2].map((k) => s.RGB[3 * at(id) + k])) };
});

const setOption = async (page, name, value) => {
  await page.fill(`#step-results fieldset.uncertainty input[data-option="${name}"]`, String(value));
  await page.dispatchEvent(`#step-results fieldset.uncertainty input[data-option="${name}"]`, 'change');
};

pageTest('bootstrap: progress, cancel, intervals equal the CLI\'s, ellipses drawn', { timeout: 600000, open }, async ({ page }) => {
  await fitOne(page);
  // The form is the engine's table: its bounds and defaults.
  const max = await page.getAttribute('#step-results fieldset.uncertainty input[data-option="resamples"]', 'max');
  assert.equal(max, '100000');

  // Cancel: a long run stops where it is, and nothing is kept.
  await setOption(page, 'resamples', 100000);
  await page.click('#step-results button[data-action="bootstrap"]');
  await page.waitForFunction(() => /\d+ of 100000 resamples/.test(document.querySelector('#step-results fieldset.uncertainty .progress-text')?.textContent ?? ''), null, { timeout: 60000 });
  await page.click('#step-results button[data-action="bootstrap-cancel"]');
  const cancelled = await page.waitForFunction(() => {
    const t = document.querySelector('#step-results .bootstrap-note')?.textContent ?? '';
    return /^Cancelled after/.test(t) ? t : null;
  }, null, { timeout: 30000 }).then((h) => h.jsonValue());
  const doneAtCancel = Number(/after (\d+) of/.exec(cancelled)[1]);
  assert.ok(doneAtCancel > 0 && doneAtCancel < 100000, cancelled);
  assert.equal(await page.evaluate(() => window.tristim.session.results[0].bootstrap), undefined);

  // N = 200, seed 3, level 0.9.
  await setOption(page, 'resamples', 200);
  await setOption(page, 'seed', 3);
  await setOption(page, 'level', 0.9);
  await page.click('#step-results button[data-action="bootstrap"]');
  await page.waitForSelector('#step-results table.coefficients', { timeout: 60000 });
  const r = await training(page);
  // The sampled RAW's pixels were resampled too; their σ is of the fitted (identity-linearised) values.
  assert.equal(r.bootstrap.resampling, 'patches+pixels');
  assert.deepEqual(r.rgb, r.sampledRGB);
  assert.match(await page.textContent('#step-results .bootstrap-summary p.summary'), /over the patches and each patch's pixels/);
  // The same training set, pixel statistics and recipe through the CLI.
  writeTraining(r);
  const cli = JSON.parse(execFileSync(CLI, ['fit', '--recipe', artifact('bootstrap-recipe.json'), '--rgb', artifact('bootstrap-rgb.csv'),
    '--xyz', artifact('bootstrap-xyz.csv'), '--bootstrap', '200', '--seed', '3', '--level', '0.9'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
  const { train_ci, loo_ci, ...page_ } = r.bootstrap;
  assert.deepEqual(page_, cli.bootstrap);
  assert.deepEqual(train_ci, cli.metrics.training.dE00.ci);
  assert.deepEqual(loo_ci, cli.metrics.loo.dE00.ci);
  // The exported profile carries the covariance and the intervals.
  const exported = JSON.parse(r.profile);
  assert.deepEqual(exported.bootstrap.covariance, cli.bootstrap.covariance);
  assert.deepEqual(exported.metrics.loo.dE00.ci, cli.metrics.loo.dE00.ci);

  // Shown: intervals next to the training and leave-one-out means, each coefficient's, ellipses.
  const cell = (col) => page.textContent(`#step-results table.compare td[data-col="${col}"] small.ci`);
  const f = (v) => v.toFixed(2);
  assert.match(await cell('train-mean'), new RegExp(`\\[${f(train_ci.lo)}, ${f(train_ci.hi)}\\]`));
  assert.match(await cell('loo-mean'), new RegExp(`\\[${f(loo_ci.lo)}, ${f(loo_ci.hi)}\\]`));
  assert.equal(await page.$$eval('#step-results table.coefficients td small.ci', (e) => e.length), 9);
  const ellipses = async (plot) => page.$$eval(`figure[data-plot="${plot}"] g.ellipse path`, (e) => e.length);
  assert.equal(await ellipses('xy-arrows'), r.ids.length);
  assert.equal(await ellipses('lab-a-b'), r.ids.length);
  assert.match(await page.textContent('figure[data-plot="lab-a-b"] figcaption'), /90 % region over 200 bootstrap refits/);
  await page.$eval('#step-results fieldset.uncertainty', (e) => e.scrollIntoView());
  await screenshot(page, 'bootstrap-results');
  await page.$eval('figure[data-plot="lab-a-b"]', (e) => e.scrollIntoView());
  await screenshot(page, 'bootstrap-ellipses');
});

pageTest('leave-one-out checks: the stopping-point flag and the ridge row are tristim compare --ridge\'s', { timeout: 600000, open }, async ({ page }) => {
  await fitOne(page, 'Finlayson2015-3', 'de2000');
  await page.click('#step-results button[data-action="loo-checks"]');
  await page.waitForSelector('#step-results table.ridge tbody tr', { timeout: 120000 });
  const r = await training(page);
  writeTraining(r);
  const white = JSON.parse(r.profile).recipe.characterisation.lab_white.join(',');
  const cli = JSON.parse(execFileSync(CLI, ['compare', '--rgb', artifact('bootstrap-rgb.csv'), '--xyz', artifact('bootstrap-xyz.csv'),
    '--models', 'Finlayson2015-3', '--objectives', 'de2000', '--ridge', '--json', '--lab-white', white], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
  const stop = cli.rows[0].loo_stopping;
  const flag = await page.textContent('#step-results table.compare:not(.ridge) td.status');
  if (stop.flagged) assert.match(flag, new RegExp(`LOO-unstable: ${stop.perturbed_loo_mean.toFixed(2)} with 100× tighter stopping`));
  else assert.match(flag, /LOO stable/);
  const ridge = await page.$$eval('#step-results table.ridge tbody tr td', (e) => e.map((x) => x.textContent));
  const c = cli.ridge[0];
  assert.deepEqual(ridge.slice(0, 4), [c.train_dE00.mean.toFixed(2), c.loo_dE00.mean.toFixed(2), c.loo_dE00.max.toFixed(2), c.lambda.toExponential(2)]);
  await page.$eval('#step-results table.compare', (e) => e.scrollIntoView());
  await screenshot(page, 'loo-checks');
});

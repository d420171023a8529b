// The first visit (fresh browser profile, nothing stored): the engine starts in a worker with every
// function the page calls, and the first screen is the example chart already sampled and fitted
// (issue 5: "the README's serve command opens with the example chart already sampled and fitted").
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { openBrowser, screenshot, repoRoot } from './harness.mjs';
import { loadTristim } from '../wasm/load.mjs';

/// Names of the engine functions the page's code calls (`T.name(`), from web/.
function engineCalls(dir = path.join(repoRoot, 'web'), out = new Set()) {
  for (const e of fs.readdirSync(dir, { withFileTypes: true })) {
    const p = path.join(dir, e.name);
    if (e.isDirectory()) engineCalls(p, out);
    else if (p.endsWith('.js')) for (const m of fs.readFileSync(p, 'utf8').matchAll(/\bT\.(\w+)\(/g)) out.add(m[1]);
  }
  return [...out];
}
import { waitReady, marks, markCounts, pageTest } from './journey.mjs';

pageTest('first screen: the example is sampled and fitted, engine in a worker, no console error or off-origin request', { problems: false, open: openBrowser }, async (b) => {
  const { page } = b;
  await page.goto(b.origin + '/');
  await page.waitForSelector('#engine-status[data-ready="true"]', { timeout: 30000 });
  assert.match(await page.textContent('#engine-status'), /tristim \d+\.\d+\.\d+ ready/);
  const csp = await page.evaluate(() => document.querySelector('meta[http-equiv="Content-Security-Policy"]')?.content);
  assert.match(csp, /default-src 'self'/);
  // Every engine function the page calls (T.name( in web/) exists in this build.
  const T = await loadTristim();
  assert.ok(engineCalls().length > 20, `the scan finds the page's engine calls: ${engineCalls()}`);
  assert.deepEqual(engineCalls().filter((f) => typeof T[f] !== 'function'), []);

  await waitReady(page);
  // The engine's worker is boot.js's, taken over by main.js (no second one), besides the pool's.
  const poolSize = await page.evaluate(() => window.tristim.views.fit.pool.clients.length);
  assert.equal(page.workers().length, 1 + poolSize, `workers: ${page.workers().map((w) => w.url())}`);
  // Nothing was stored before: this is the example, shown on the Results step.
  assert.equal(await page.evaluate(() => document.body.dataset.step), 'results');
  assert.equal(await page.isVisible('#step-results'), true);
  assert.equal(await page.isHidden('#step-images'), true);
  assert.equal(await page.evaluate(() => window.tristim.session['files.chart']?.name), 'passport.dng');
  assert.match(await page.textContent('#step-results .example-note'), /built-in example/);
  // Sampled: 24 patches of the Passport, with the example's preset corners.
  assert.equal(await page.evaluate(() => window.tristim.derived.sample?.ids.length), 24);
  assert.equal(await page.locator('#step-images .patch-table tbody tr').count(), 24);
  // Fitted: every model × objective compared (refused rows are in the fit log), each row with
  // finite training and LOO errors.
  const total = T.listModels().filter((m) => !m.duplicate_of).length * T.listObjectives().length;
  const n = await page.evaluate(() => window.tristim.session.results.length);
  assert.match(await page.textContent('#step-fit .fit-log li:last-child'), new RegExp(`^${n} of ${total} fits in`));
  const rows = page.locator('#step-results table.compare tbody tr');
  assert.ok(n > total / 2, `${n} of ${total} rows fitted`);
  assert.equal(await rows.count(), n);
  // A CIEDE2000 row names the loss it minimised (the default: the mean, by reweighted LM).
  const de2000Labels = await page.evaluate(() => window.tristim.session.results.filter((r) => r.objective === 'de2000').map((r) => r.label));
  assert.ok(de2000Labels.length > 5 && de2000Labels.every((l) => / · CIEDE2000 mean \(reweighted Levenberg-Marquardt\)$/.test(l)), de2000Labels.join('; '));
  // (a model with as many terms as patches less one has no leave-one-out figure: '–')
  const withLoo = await page.evaluate(() => window.tristim.session.results.filter((r) => r.fit.evaluation.has_loo).length);
  assert.ok(withLoo > n - 5, `${withLoo} of ${n} rows have a leave-one-out figure`);
  for (const [col, count] of [['train-mean', n], ['loo-mean', withLoo]]) {
    const v = (await page.locator(`#step-results table.compare tbody td[data-col="${col}"]`).allTextContents()).map(Number).filter(Number.isFinite);
    assert.ok(v.length === count && v.every((x) => x >= 0), `${col}: ${v}`);
  }
  // Every plot of the selected model has its data marks (24 patches).
  const need = { 'xy-arrows': 24, 'lab-a-L': 48, 'lab-C-L': 48, 'de2000-bars': 72, 'xyz-scatter': 72, 'swatch-pairs': 48 };
  for (const [name, min] of Object.entries(need)) {
    const m = await marks(page, name);
    assert.ok(m >= min, `${name}: ${m} marks, expected ≥ ${min} (${JSON.stringify(await markCounts(page, name))})`);
  }
  assert.equal(await page.locator('[data-unavailable]').count(), 0);
  // The objectives' options forms come from the engine's table: the CIEDE2000 default is its 'auto'.
  assert.equal(await page.$eval('#step-fit details[data-objective="de2000"] select[data-option="algorithm"]', (s) => s.value), 'auto');
  assert.equal(await page.$eval('#step-fit details[data-objective="psm"] input[data-option="expansion"]', (i) => i.value), '2');
  // The session holds the Recipe the selected fit was made with.
  const recipe = await page.evaluate(() => window.tristim.store.get('recipe'));
  assert.equal(recipe.sampling.layout.chart, 'passport');
  assert.ok(T.listObjectives().some((o) => o.id === recipe.characterisation.objective.method), recipe.characterisation.objective.method);
  assert.equal(recipe.reference.illuminant, 'D50');
  await screenshot(page, 'first-screen');
  assert.deepEqual(b.problems, []);

  // The net the other tests rely on: an unhandled rejection or uncaught error inside the worker
  // reaches the console, so the harness records it.
  const [worker] = page.workers();
  assert.ok(worker, 'the engine runs in a worker');
  await worker.evaluate(() => { Promise.reject(new Error('probe: rejection in the worker')); });
  await worker.evaluate(() => { setTimeout(() => { throw new Error('probe: error in the worker'); }); });
  for (const probe of [/unhandled rejection: .*probe: rejection in the worker/, /uncaught error: .*probe: error in the worker/]) {
    const t0 = Date.now();
    while (!b.problems.some((p) => probe.test(p)) && Date.now() - t0 < 10000) await new Promise((r) => setTimeout(r, 50));
    assert.ok(b.problems.some((p) => probe.test(p)), `${probe} recorded: ${JSON.stringify(b.problems)}`);
  }
});

pageTest('without boot.js (it did not run) main.js starts the engine and the example itself', { open: openBrowser }, async (b) => {
  const { page } = b;
  await page.route('**/boot.js', (r) => r.fulfill({ status: 200, contentType: 'text/javascript', body: '' }));
  await page.goto(b.origin + '/');
  await waitReady(page);
  assert.equal(await page.evaluate(() => window.tristim.derived.sample?.ids.length), 24);
  assert.ok(await page.evaluate(() => window.tristim.session.results.length) > 10);
  const poolSize = await page.evaluate(() => window.tristim.views.fit.pool.clients.length);
  assert.equal(page.workers().length, 1 + poolSize);
});

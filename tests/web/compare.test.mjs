// Step 3 compares everything by default (issue 13): every model × objective, each with
// leave-one-out, spread over a few workers, rows streaming into the results table with progress
// (rows done / total); the table's figures are the module's `compareModels` output for the same
// patches; Cancel stops the rows (none arrives afterwards) and the page stays usable.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { step, noErrorNear, pageTest } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

// Page and module are the same wasm binary on the same inputs: the numbers should be identical.
// Stated tolerance 1e-9 relative (the worst difference is printed).
const REL_TOL = 1e-9;
const fmt = (x) => (Number.isFinite(x) ? x.toFixed(2) : '–');   // web/lib/ui.js fmt

/// Records what the page says while it compares: every 'compare' progress event and the number
/// of result rows each time the results are redrawn.
const record = (page) => page.evaluate(() => {
  window.__cmp = { progress: [], rows: [] };
  window.tristim.on('compare', (e) => window.__cmp.progress.push({ ...e }));
  window.tristim.on('results', (r) => window.__cmp.rows.push(r.length));
});
const summary = (page) => page.waitForFunction(() => {
  const t = document.querySelector('#step-fit .fit-log li:last-child')?.textContent ?? '';
  return /fits in [\d.]+ s\.$|^Cancelled after/.test(t) ? t : null;
}, null, { timeout: 300000 }).then((h) => h.jsonValue());

pageTest('the fit step compares every model × objective by default, streaming rows with the module\'s compare numbers; cancel stops it', async (b) => {
  const { page } = b;
  const T = await loadTristim();
  const models = T.listModels().filter((m) => !m.duplicate_of).map((m) => m.id);
  const objectives = T.listObjectives().map((o) => o.id);
  const total = models.length * objectives.length;

  // 1. The default choice is everything (duplicates of another model's span left out).
  await step(page, 'fit');
  const checked = (attr) => page.$$eval(`#step-fit input[data-${attr}]`, (els, a) => els.filter((e) => e.checked).map((e) => e.dataset[a]), attr);
  assert.deepEqual((await checked('model')).sort(), [...models].sort());
  assert.deepEqual(await checked('objective'), objectives);

  // 2. Run it from the button: progress reaches total, rows stream in (the table grows in steps).
  await record(page);
  await page.click('#step-fit button.primary');
  const line = await summary(page);
  const m = /^(\d+) of (\d+) fits in ([\d.]+) s\.$/.exec(line);
  assert.ok(m, line);
  assert.equal(Number(m[2]), total);
  const { progress, rows } = await page.evaluate(() => window.__cmp);
  const last = progress[progress.length - 1];
  assert.deepEqual({ done: last.done, total: last.total, running: last.running }, { done: total, total, running: false });
  assert.ok(progress.every((p, i) => i === 0 || p.done >= progress[i - 1].done), 'progress never goes back');
  assert.ok(new Set(rows).size >= 3 && rows[0] < rows[rows.length - 1], `rows streamed into the table: ${rows}`);
  assert.equal(await page.evaluate(() => document.body.dataset.step), 'results', 'the button shows the results step');
  assert.ok(await noErrorNear(page, '#step-fit button.primary'));
  // The log lists the rows as the models and objectives are listed on the step (model by model),
  // not in the order they finished; the summary stays last.
  const listed = await page.$$eval('#step-fit input[data-model]', (els) => els.map((e) => e.dataset.model));
  const logged = await page.$$eval('#step-fit .fit-log li[data-model]', (els) => els.map((e) => `${e.dataset.model}|${e.dataset.objective}`));
  assert.deepEqual(logged, listed.filter((id) => models.includes(id)).flatMap((id) => objectives.map((o) => `${id}|${o}`)));
  console.log(`compare in the page: ${line} (${await page.evaluate(() => window.tristim.views.fit.pool.size)} workers)`);

  // 3. The table's figures are the module's compareModels on the same patches.
  const page_ = await page.evaluate(() => {
    const rs = window.tristim.session.results;
    return {
      rgb: Array.from(rs[0].rgb), xyz: Array.from(rs[0].xyz), white: Array.from(rs[0].white),
      sameData: rs.every((r) => r.rgb.every((v, i) => v === rs[0].rgb[i]) && r.xyz.every((v, i) => v === rs[0].xyz[i])),
      rows: rs.map((r) => ({ key: r.key, model: r.modelId, objective: r.objective, train: r.fit.evaluation.training.dE00, loo: r.fit.evaluation.loo?.dE00 ?? null,
        cells: Object.fromEntries([...document.querySelectorAll(`#step-results table.compare tbody tr[data-key="${CSS.escape(r.key)}"] td[data-col]`)].map((td) => [td.dataset.col, td.textContent])) })),
      refused: [...document.querySelectorAll('#step-fit .fit-log li.error')].map((li) => ({ text: li.textContent, code: li.dataset.code })),
    };
  });
  assert.ok(page_.rows.every((r) => r.cells['train-mean'] !== undefined), 'every result has its table row');
  assert.equal(await page.locator('#step-results table.compare tbody tr').count(), page_.rows.length);
  assert.ok(page_.sameData, 'every row was fitted on the same patches (no surface stage)');
  const cmp = T.compareModels(Float64Array.from(page_.rgb), Float64Array.from(page_.xyz), { white: page_.white }, models, objectives, -1);
  assert.equal(cmp.length, total);
  let worst = { rel: 0 };
  const refusedByModule = [];
  for (const c of cmp) {
    const obj = c.objective;  // its id, as tristim compare --json prints it
    const r = page_.rows.find((x) => x.model === c.model && x.objective === obj);
    if (!c.ok) {
      refusedByModule.push(c.model);
      assert.equal(r, undefined, `${c.model} ${obj}: refused by the module (${c.error_code}) but in the page's table`);
      assert.ok(page_.refused.some((x) => x.code === c.error_code && x.text.includes(c.model)), `${c.model} ${obj}: the page's log says ${c.error_code}`);
      continue;
    }
    assert.ok(r, `${c.model} ${obj}: in compareModels, not in the page's table`);
    assert.equal(r.loo !== null, c.has_loo, `${c.model} ${obj}: leave-one-out present in both`);
    const pairs = [['train-mean', r.train.mean, c.train_dE00.mean], ['train-max', r.train.max, c.train_dE00.max]];
    if (c.has_loo) pairs.push(['loo-mean', r.loo.mean, c.loo_dE00.mean], ['loo-max', r.loo.max, c.loo_dE00.max]);
    for (const [col, got, want] of pairs) {
      const rel = Math.abs(got - want) / Math.max(Math.abs(want), 1e-12);
      if (rel > worst.rel) worst = { rel, what: `${c.model} ${obj} ${col}`, got, want };
      assert.equal(r.cells[col], fmt(want), `${c.model} ${obj} ${col}: the table shows ${r.cells[col]}, compareModels ${want}`);
    }
  }
  assert.equal(page_.rows.length + page_.refused.length, total);
  console.log(`page vs compareModels: ${cmp.length} rows (${refusedByModule.length} refused by both), worst relative difference ${worst.rel}` +
    (worst.what ? ` (${worst.what}: page ${worst.got}, module ${worst.want})` : '') + `, tolerance ${REL_TOL}`);
  assert.ok(worst.rel <= REL_TOL, `worst: ${JSON.stringify(worst)}`);
  // Sorted by leave-one-out mean; the best is marked and (nothing else picked) shown.
  const looCells = (await page.locator('#step-results table.compare tbody td[data-col="loo-mean"]').allTextContents()).map(Number).filter(Number.isFinite);
  assert.deepEqual(looCells, [...looCells].sort((a, b) => a - b));
  const bestRow = cmp.filter((c) => c.ok && c.has_loo).reduce((a, c) => (c.loo_dE00.mean < a.loo_dE00.mean ? c : a));
  assert.match(await page.textContent('#step-results table.compare tbody tr.best th'), new RegExp(`best`));
  assert.equal(await page.getAttribute('#step-results table.compare tbody tr.best', 'data-key'),
    page_.rows.find((r) => r.model === bestRow.model && r.objective === bestRow.objective).key);
  assert.equal(await page.getAttribute('#step-results table.compare tbody tr.selected', 'data-key'), await page.getAttribute('#step-results table.compare tbody tr.best', 'data-key'));
  await screenshot(page, 'compare-everything');

  // 4. Cancel: after a few rows, no row arrives any more, the workers are gone, the page works.
  await step(page, 'fit');
  await record(page);
  await page.click('#step-fit button.primary');
  await page.waitForFunction(() => (window.__cmp.progress.at(-1)?.done ?? 0) >= 3, null, { timeout: 60000 });
  const atCancel = await page.evaluate(() => { document.querySelector('#step-fit button.cancel').click(); return window.tristim.session.results.length; });
  assert.match(await summary(page), /^Cancelled after \d+ of \d+ rows/);
  await page.waitForTimeout(1500);
  const after = await page.evaluate(() => ({ n: window.tristim.session.results.length, clients: window.tristim.views.fit.pool.clients.length,
    running: window.__cmp.progress.at(-1).running, done: window.__cmp.progress.at(-1).done, total: window.__cmp.progress.at(-1).total }));
  assert.equal(after.n, atCancel, 'no row arrives after Cancel');
  assert.equal(after.clients, 0, 'the compare\'s workers are terminated');
  assert.equal(after.running, false);
  assert.ok(after.done < after.total, `cancelled before the end (${after.done} of ${after.total})`);
  assert.equal(await page.isEnabled('#step-fit button.primary'), true);
  assert.equal(await page.isHidden('#step-results .compare-progress'), true);
  // The rows finished before Cancel are kept and shown.
  assert.equal(await page.locator('#step-results table.compare tbody tr').count(), atCancel);

  // The page stays usable: one short fit runs to the end (on fresh workers).
  await step(page, 'fit');
  for (const [attr, keep] of [['model', 'matrix-3x3'], ['objective', 'ls']]) {
    const boxes = page.locator(`#step-fit input[data-${attr}]`);
    for (let i = 0; i < await boxes.count(); i++) await boxes.nth(i).setChecked(await boxes.nth(i).getAttribute(`data-${attr}`) === keep);
  }
  await page.click('#step-fit button.primary');
  assert.match(await summary(page), /^1 of 1 fits/);
  assert.equal(await page.locator('#step-results table.compare tbody tr').count(), 1);
});

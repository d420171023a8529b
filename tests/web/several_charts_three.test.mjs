// Three chart images in one fit (issue 48, docs/multi-image.md): the example's Passport, chart image
// 2 — a ColorChecker drawn as a plain 4×6 grid, sampled with a custom grid and paired with its own
// reference file — and chart image 3 (added with "Add chart image") — a ColorChecker with veiling
// flare, whose own light trap (over its black patch) is subtracted before sampling. The profile's
// recipe lists the three images with their layouts, reference and capture; `tristim fit --recipe r.json
// --raw a --raw b --raw c --xyz rb.csv` gives the page's coefficients and per-chart figures to the bit;
// the share link (a reference-file chart among its images) reproduces with `tristim reproduce` and in
// a fresh browser, and so does the project file, whose link names the three source images; a reload restores the three images; removing image 2 moves image 3 into its place. The charts are rendered by `tristim lab
// render` at test time.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync, spawnSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, upload, fitMatrix3x3, waitReady, CLI, artifact, DNG } from './journey.mjs';
import { assertCliEqual, openShared } from './several_charts_common.mjs';

const PANEL = (k) => `#step-images fieldset.second-chart[data-slot="chart${k}"]`;
const TRAP = { x: 410, y: 266, w: 16, h: 16 };   // inside chart image 3's D6 (its black patch)

/// {grid: {path, reference, rows, columns, corners}, flare: path}: the two rendered charts.
function renderFiles() {
  const render = (args, name) => {
    const out = artifact(name);
    const truth = JSON.parse(execFileSync(CLI, ['lab', 'render', '--camera', 'Canon_EOS_5D_Mark_II', '--illuminant', 'D65', '--size', '600x400', ...args, '--out', out]));
    return { path: out, truth };
  };
  const reference = artifact('three-grid-reference.csv');
  const grid = render(['--reflectances', 'cc24', '--reference-out', reference], 'three-grid.dng');
  const flare = render(['--chart', 'cc24', '--flare', '0.01', '--corners', '150,80,450,90,440,300,160,310'], 'three-flare.dng');
  const args = grid.truth.sample_args.split(' ');   // `tristim sample` options: --chart custom --rows R --columns C --corners …
  const opt = (name) => args[args.indexOf(name) + 1];
  return { grid: { path: grid.path, reference, rows: opt('--rows'), columns: opt('--columns'), corners: opt('--corners').split(',').map(Number) }, flare: flare.path };
}

/// Waits until chart image k's panel is sampled, then until check([panel selector, k, arg]) holds (run in the page).
const sampled = (page, k, check, arg = null) => page.waitForFunction(([sel, k2]) => {
  const p = document.querySelector(sel), s = window.tristim.derived[`sample${k2}`];
  return p?.dataset.state === 'sampled' && !!s;
}, [PANEL(k), k], { timeout: 60000 }).then(() => page.waitForFunction(check, [PANEL(k), k, arg], { timeout: 60000 }));

pageTest('three chart images (a custom grid with its reference file, a light trap of its own): equal to tristim fit --recipe --raw a --raw b --raw c; the link reproduces', { timeout: 400000 }, async ({ page }) => {
  const files = renderFiles();
  await step(page, 'images');
  // Chart image 2: a custom grid of the rendered chart's rows and columns, at the render's corners.
  await upload(page, `${PANEL(2)} input[data-slot="chart2"]`, 'grid.dng', fs.readFileSync(files.grid.path));
  await page.waitForFunction((sel) => document.querySelector(sel)?.dataset.state !== 'empty', PANEL(2), { timeout: 60000 });
  await page.selectOption(`${PANEL(2)} select[data-role="chart2-chart"]`, 'custom');
  for (const [name, v] of [['rows', files.grid.rows], ['columns', files.grid.columns], ['gap', '0']]) {
    await page.fill(`${PANEL(2)} input[data-layout="${name}"]`, v);
    await page.dispatchEvent(`${PANEL(2)} input[data-layout="${name}"]`, 'change');
  }
  await page.evaluate((c) => { const ed = window.tristim.views.images.second.panel(2).editor; ed.setCorners(c); ed.onChange(ed.corners, true); }, files.grid.corners);
  await page.setInputFiles(`${PANEL(2)} input[data-role="chart2-reference"]`, files.grid.reference);
  await page.waitForFunction((sel) => /three-grid-reference\.csv: 24 patches/.test(document.querySelector(sel)?.textContent), `${PANEL(2)} .second-frames`, { timeout: 30000 });
  await sampled(page, 2, ([sel, k, x0]) => { const s = window.tristim.derived[`sample${k}`]; return s.ids.length === 24 && s.ids[0] === 'R1C1' && s.corners[0] === x0; }, files.grid.corners[0]);

  // Chart image 3: added, a ColorChecker found by detection, its light trap over its black patch.
  await page.click('#step-images button.add-image');
  await upload(page, `${PANEL(3)} input[data-slot="chart3"]`, 'flare.dng', fs.readFileSync(files.flare));
  await page.selectOption(`${PANEL(3)} select[data-role="chart3-chart"]`, 'cc24');
  await sampled(page, 3, ([sel, k]) => { const s = window.tristim.derived[`sample${k}`]; return s.ids.length === 24 && s.ids[0] === 'A1'; });
  const before = await page.evaluate(() => Array.from(window.tristim.derived.sample3.patches[0].mean));
  await page.check(`${PANEL(3)} fieldset.light-trap input[type=checkbox]`);
  for (const [k, v] of Object.entries({ x: TRAP.x, y: TRAP.y, width: TRAP.w, height: TRAP.h })) {
    await page.fill(`${PANEL(3)} input[data-trap="${k}"]`, String(v));
    await page.dispatchEvent(`${PANEL(3)} input[data-trap="${k}"]`, 'change');
  }
  await sampled(page, 3, ([sel, k, t]) => {
    const p = document.querySelector(sel), s = window.tristim.derived[`sample${k}`];
    return p.dataset.trap === 'subtracted' && s.lightTrapCorners?.[0] === t.x && s.lightTrapCorners[5] === t.y + t.h;
  }, TRAP);
  const trap = await page.evaluate(() => { const s = window.tristim.derived.sample3; return { mean: Array.from(s.lightTrap.mean), a1: Array.from(s.patches[0].mean) }; });
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(trap.a1[c] - (before[c] - trap.mean[c])) < 1e-6 * before[c], `A1 channel ${c}: ${before[c]} − flare ${trap.mean[c]}`);
  assert.match(await page.textContent(`${PANEL(3)} .light-trap-state`), /Flare subtracted/);
  await screenshot(page, 'several-charts-three');

  await fitMatrix3x3(page);
  const made = await page.evaluate(() => {
    const t = window.tristim, r = t.session.results.find((x) => x.key === t.session.selected);
    return { profile: JSON.parse(r.fit.profile), charts: r.fit.charts, ids: Array.from(r.ids) };
  });
  assert.match(await page.textContent('#step-fit .summary'), /and the 48 patches of chart images 2–3 \(grid\.dng, flare\.dng, step 2\): one fit on all/);
  const { images } = made.profile.recipe;
  assert.deepEqual(images.map((e) => e.name), ['passport.dng', 'grid.dng', 'flare.dng']);
  assert.deepEqual(images[1].sampling.layout, { chart: 'custom', rows: Number(files.grid.rows), columns: Number(files.grid.columns), margins: [0, 0, 0, 0], gap: 0 });
  assert.equal(images[1].reference.chart, 'file');
  assert.equal(images[2].sampling.layout.chart, 'cc24');
  assert.deepEqual(images[2].capture.light_trap, [TRAP.x, TRAP.y, TRAP.x + TRAP.w, TRAP.y, TRAP.x + TRAP.w, TRAP.y + TRAP.h, TRAP.x, TRAP.y + TRAP.h]);
  assert.deepEqual(images[2].capture.flare, trap.mean);
  assert.ok(!images[1].capture?.light_trap && !images[0].capture.light_trap, 'the trap is chart image 3\'s alone');
  assert.equal(made.charts.length, 3);
  assertCliEqual(made.profile, made.charts, ['--raw', DNG, '--raw', files.grid.path, '--raw', files.flare, '--xyz', files.grid.reference], 'three');

  // The share link: `tristim reproduce` and a fresh browser recompute the three-image profile.
  await step(page, 'share');
  await page.click('#share-make');
  await page.waitForFunction(() => document.getElementById('share-link').value.includes('#tristim='), null, { timeout: 120000 });
  const link = await page.inputValue('#share-link');
  const rep = spawnSync(CLI, ['reproduce', link], { encoding: 'utf8' });
  assert.equal(rep.status, 0, rep.stderr);
  assert.match(rep.stdout, /^reproduced/);
  await openShared(link, async (fresh) => {
    assert.deepEqual(await fresh.$$eval('#share-verdict .share-charts li', (li) => li.map((x) => x.textContent)), ['1: passport.dng', '2: grid.dng', '3: flare.dng']);
    const again = await fresh.evaluate(async (text) => JSON.parse((await window.tristim.engine.call('openLink', { text })).profile), link);
    assert.deepEqual(again.model.coefficients, made.profile.model.coefficients, 'the link\'s coefficients, to the bit');
  });

  // The project file names and carries the three images: `tristim reproduce` samples each again.
  const project = artifact('three.tristim');
  const [download] = await Promise.all([page.waitForEvent('download', { timeout: 120000 }), page.click('#share-export')]);
  await download.saveAs(project);
  const proj = spawnSync(CLI, ['reproduce', project], { encoding: 'utf8' });
  assert.equal(proj.status, 0, proj.stderr + proj.stdout);
  assert.match(proj.stdout, /^reproduced/);
  const opened = await page.evaluate(async (bytes) => {
    const p = await window.tristim.engine.call('projectOpen', { bytes: new Uint8Array(bytes) });
    return { images: p.images.map((i) => i.name), sources: JSON.parse(p.reproduction.payload).sources.map((s) => s.name) };
  }, Array.from(fs.readFileSync(project)));
  assert.deepEqual(opened.sources, ['passport.dng', 'grid.dng', 'flare.dng'], 'the project\'s link names the three source images');
  for (const name of opened.sources) assert.ok(opened.images.includes(name), `the project holds ${name}`);

  // A reload restores the three images: the custom grid with its reference, the trap subtracted.
  await page.reload();
  await waitReady(page);
  await step(page, 'images');
  await sampled(page, 2, ([sel, k]) => window.tristim.derived[`sample${k}`].ids[0] === 'R1C1' && document.querySelector(`${sel} select[data-role="chart2-chart"]`).value === 'custom');
  await sampled(page, 3, ([sel]) => document.querySelector(sel).dataset.trap === 'subtracted');
  assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.derived.sample3.lightTrap.mean)), trap.mean);
  assert.match(await page.textContent(`${PANEL(2)} .second-frames`), /three-grid-reference\.csv: 24 patches/);

  // Removing chart image 2 moves chart image 3 (its file, layout and light trap) into its place.
  await page.click(`${PANEL(2)} button.remove-image`);
  await sampled(page, 2, ([sel]) => document.querySelector(sel).dataset.trap === 'subtracted' && /^flare\.dng/.test(document.querySelector(`${sel} .file-state`).textContent));
  assert.equal(await page.locator('#step-images fieldset.second-chart').count(), 1);
  const left = await page.evaluate(() => {
    const t = window.tristim;
    return { keys: Object.keys(t.session).filter((k) => /^chart\d/.test(k) && t.session[k]), chart: t.session.chart2.chart, trap: Array.from(t.derived.sample2.lightTrap.mean) };
  });
  assert.deepEqual(left, { keys: ['chart2'], chart: 'cc24', trap: trap.mean });
});

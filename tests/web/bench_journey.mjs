// Speed of the page (not part of the test run): prints, in headless Chromium,
//  1. the first screen of a new session with the module cached (the example DNG decoded, sampled,
//     compared — every model × objective with leave-one-out — and plotted): when the first row's
//     plots are drawn, and when the whole compare is in;
//  2. time from dropping the Passport DNG (corners preset) to the compare done and plots drawn;
//  3. time from choosing the 8.2 MP Canon 30D CR2 to its luminance map shown (decode + apply);
// next to the native CLI doing the same work, when build/native/core/tristim exists. The load
// average is printed with the figures (browser timings are noisy on a busy machine).
// usage: node tests/web/bench_journey.mjs [runs]
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { repoRoot } from './harness.mjs';
import { openPage, step, upload, fileBuffer, waitReady, DNG, CR2 } from './journey.mjs';

const runs = Number(process.argv[2] ?? 3);
const example = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const load = () => os.loadavg().map((x) => x.toFixed(2)).join(', ');
console.log(`machine: ${os.cpus().length} × ${os.cpus()[0]?.model}; load average at start ${load()}`);

const b = await openPage();
const { page } = b;
const first = [], all = [], chart = [], chartFirst = [], cr2 = [];
const armTimer = (sel) => page.evaluate((q) => {
  document.querySelector(q).addEventListener('change', () => { window.__t0 = performance.now(); }, { capture: true, once: true });
}, sel);
const elapsed = () => page.evaluate(() => Math.round(performance.now() - window.__t0));
let nRows = 0, workers = 0;
try {
  // 1. First screen: a new session (the store cleared) reloaded; the module is in the browser's cache.
  for (let k = 0; k < runs; k++) {
    await page.evaluate(() => window.tristim.store.clear());
    await page.reload();
    await waitReady(page, 120000);
    const t = await page.evaluate(() => Object.fromEntries(['tristim:first-screen', 'tristim:ready'].map((n) => [n, performance.getEntriesByName(n)[0]?.startTime])));
    first.push(Math.round(t['tristim:first-screen']));
    all.push(Math.round(t['tristim:ready']));
  }
  nRows = await page.evaluate(() => window.tristim.session.results.length);
  workers = await page.evaluate(() => window.tristim.views.fit.pool.size);

  for (let k = 0; k < runs; k++) {
    // 2. The DNG dropped: decoded, sampled, compared, plotted.
    await step(page, 'images');
    await page.evaluate((cs) => window.tristim.save('corners', cs), example.corners);
    // Time from the input's change event (the drop), measured in the page: the upload through
    // the test protocol is not part of what a user waits for.
    await armTimer('#step-images input[data-slot="chart"]');
    // The fit starts on the new file's sample (the previous file's 24-row table is still shown
    // while the new one decodes: starting then fitted the old sample, racing the decode).
    await page.evaluate(() => { window.__oldSample = window.tristim.derived.sample; });
    await upload(page, '#step-images input[data-slot="chart"]', `passport-${k}.dng`, fileBuffer(DNG));
    await page.waitForFunction((n) => (document.querySelector('#step-images .file-state')?.textContent ?? '').includes(n), `passport-${k}.dng`, { timeout: 60000 });
    await page.waitForFunction(() => window.tristim.derived.sample && window.tristim.derived.sample !== window.__oldSample
      && document.querySelectorAll('#step-images .patch-table tbody tr').length === 24, null, { timeout: 60000 });
    // Returns nothing: handing the 48 results back to node would serialise them on the page's thread
    // (~0.2 s inside the measured time, which a user does not wait for).
    await page.evaluate(async () => { await window.tristim.views.fit.run({ onFirst: () => { window.__first = performance.now(); window.tristim.goto('results'); } }); });
    await page.waitForFunction(() => document.querySelectorAll('figure[data-plot="de2000-bars"] svg g[aria-label] rect').length > 0, null, { timeout: 120000 });
    chart.push(await elapsed());
    chartFirst.push(await page.evaluate(() => Math.round(window.__first - window.__t0)));

    // 3. The CR2 chosen in step 5: decoded, the selected profile applied, the Y map shown.
    await step(page, 'apply');
    await page.selectOption('#step-apply select >> nth=0', 'scene');
    await armTimer('#step-apply input[type=file]');
    await upload(page, '#step-apply input[type=file]', `scene-${k}.CR2`, fileBuffer(CR2));
    // Timed in the page when run() has drawn the map; only scalars come back (serialising the
    // rendered images for the test protocol took longer than drawing them and was counted).
    const r = await page.evaluate(async () => {
      const o = await window.tristim.views.apply.run();
      window.__t1 = performance.now();
      return o && { fullWidth: o.fullWidth, fullHeight: o.fullHeight, msApply: o.msApply, msRender: o.msRender };
    });
    await page.waitForSelector('#step-apply .legend-box');
    cr2.push(await page.evaluate(() => Math.round(window.__t1 - window.__t0)));
    if (k === 0) console.log(`CR2 applied image ${r?.fullWidth}×${r?.fullHeight}, apply ${r?.msApply?.toFixed(0)} ms, render ${r?.msRender?.toFixed(0)} ms`);
  }
  console.log(`browser (headless Chromium, ${runs} runs, median; ${nRows} compare rows fitted on ${workers} workers):`);
  console.log(`  first screen, module cached: first row plotted ${median(first)} ms, every row in ${median(all)} ms   (runs: ${first.join(', ')} / ${all.join(', ')})`);
  console.log(`  DNG dropped -> first row plotted ${median(chartFirst)} ms, every row compared ${median(chart)} ms   (runs: ${chartFirst.join(', ')} / ${chart.join(', ')})`);
  console.log(`  CR2 chosen -> decoded, profile applied, Y map shown:  ${median(cr2)} ms   (runs: ${cr2.join(', ')})`);
  console.log(`  load average after the browser runs: ${load()}`);
  if (b.problems.length) console.log('problems:', b.problems);
} finally {
  await b.close();
}

const cli = path.join(repoRoot, 'build/native/core/tristim');
if (fs.existsSync(cli)) {
  const time = (args) => { const t = process.hrtime.bigint(); try { execFileSync(cli, args, { stdio: ['ignore', 'pipe', 'pipe'], maxBuffer: 1 << 30 }); } catch (e) { return `failed: ${String(e.stderr).trim()}`; } return `${(Number(process.hrtime.bigint() - t) / 1e6).toFixed(0)} ms`; };
  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-bench-'));
  console.log('native CLI (same work):');
  console.log(`  sample the DNG: ${time(['sample', DNG, '--chart', 'passport', '--corners', example.corners.join(',')])}`);
  try {
    fs.writeFileSync(path.join(tmp, 'rgb.csv'), execFileSync(cli, ['sample', DNG, '--chart', 'passport', '--corners', example.corners.join(',')]));
    fs.writeFileSync(path.join(tmp, 'xyz.csv'), execFileSync(cli, ['reference', '--chart', 'passport', '--illuminant', 'D50']));
    console.log(`  compare every model × objective (leave-one-out): ${time(['compare', '--rgb', path.join(tmp, 'rgb.csv'), '--xyz', path.join(tmp, 'xyz.csv')])}`
      + ` (one thread: ${time(['compare', '--rgb', path.join(tmp, 'rgb.csv'), '--xyz', path.join(tmp, 'xyz.csv'), '--threads', '1'])};`
      + ' the page\'s rows in wasm one after the other: scripts/profile_page.mjs dng --node)');
    console.log(`  fit Finlayson2015-2: ${time(['fit', '--rgb', path.join(tmp, 'rgb.csv'), '--xyz', path.join(tmp, 'xyz.csv'), '--model', 'Finlayson2015-2', '--out', path.join(tmp, 'Finlayson2015-2.json')])}`);
    const applied = time(['apply', path.join(tmp, 'Finlayson2015-2.json'), CR2, '--out', path.join(tmp, 'xyz.pfm')]);
    console.log(`  apply Finlayson2015-2 to the CR2: ${applied.startsWith('failed') ? 'n/a (this CLI applies profiles to PFM images, not RAW files)' : applied}`);
    console.log(`  inspect the CR2 (metadata only): ${time(['inspect', CR2])}`);
  } catch (e) { console.log(`  (native pipeline incomplete: ${String(e.stderr ?? e.message).trim().split('\n')[0]})`); }
  console.log(`  load average: ${load()}`);
  fs.rmSync(tmp, { recursive: true, force: true });
} else console.log('native CLI not built (build/native/core/tristim): no native figures');

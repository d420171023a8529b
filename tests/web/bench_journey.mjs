// Speed of the page (not part of the test run): prints
//  1. time from dropping the Passport DNG (corners preset) to fitted results and plots drawn;
//  2. time from choosing the 8.2 MP Canon 30D CR2 to its luminance map shown (decode + apply);
// each next to the native CLI doing the same work, when build/native/core/tristim exists.
// usage: node tests/web/bench_journey.mjs [runs]
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { repoRoot } from './harness.mjs';
import { openPage, step, upload, fileBuffer, DNG, CR2 } from './journey.mjs';

const runs = Number(process.argv[2] ?? 3);
const example = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

const b = await openPage();
const { page } = b;
const chart = [], cr2 = [];
const armTimer = (sel) => page.evaluate((q) => {
  document.querySelector(q).addEventListener('change', () => { window.__t0 = performance.now(); }, { capture: true, once: true });
}, sel);
const elapsed = () => page.evaluate(() => Math.round(performance.now() - window.__t0));
try {
  for (let k = 0; k < runs; k++) {
    await step(page, 'images');
    await page.evaluate((cs) => window.tristim.save('corners', cs), example.corners);
    // Time from the input's change event (the drop), measured in the page: the upload through
    // the test protocol is not part of what a user waits for.
    await armTimer('#step-images input[data-slot="chart"]');
    await upload(page, '#step-images input[data-slot="chart"]', `passport-${k}.dng`, fileBuffer(DNG));
    await page.waitForFunction((n) => (document.querySelector('#step-images .file-state')?.textContent ?? '').includes(n), `passport-${k}.dng`, { timeout: 60000 });
    await page.waitForFunction(() => window.tristim.derived.sample && document.querySelectorAll('#step-images .patch-table tbody tr').length === 24);
    await page.evaluate(() => { delete document.body.dataset.fitted; window.tristim.on('results', () => { document.body.dataset.fitted = '1'; }); });
    await page.evaluate(() => window.tristim.views.fit.run().then(() => window.tristim.goto('results')));
    await page.waitForFunction(() => document.body.dataset.fitted === '1' && document.querySelectorAll('figure[data-plot="de2000-bars"] svg g[aria-label] rect').length > 0, null, { timeout: 120000 });
    chart.push(await elapsed());

    await step(page, 'apply');
    await page.selectOption('#step-apply select >> nth=0', 'scene');
    await armTimer('#step-apply input[type=file]');
    await upload(page, '#step-apply input[type=file]', `scene-${k}.CR2`, fileBuffer(CR2));
    const r = await page.evaluate(() => window.tristim.views.apply.run());
    await page.waitForSelector('#step-apply .legend-box');
    cr2.push(await elapsed());
    if (k === 0) console.log(`CR2 applied image ${r?.fullWidth}×${r?.fullHeight}, apply ${r?.msApply?.toFixed(0)} ms, render ${r?.msRender?.toFixed(0)} ms`);
  }
  const models = await page.evaluate(() => window.tristim.session.results.map((x) => x.label));
  console.log(`browser (headless Chromium, ${runs} runs, median):`);
  console.log(`  DNG dropped -> ${models.length} models fitted, plots drawn: ${median(chart)} ms   (runs: ${chart.join(', ')})`);
  console.log(`  CR2 chosen -> decoded, profile applied, Y map shown:  ${median(cr2)} ms   (runs: ${cr2.join(', ')})`);
  if (b.problems.length) console.log('problems:', b.problems);
} finally {
  await b.close();
}

const cli = path.join(repoRoot, 'build/native/core/tristim');
if (fs.existsSync(cli)) {
  const time = (args) => { const t = process.hrtime.bigint(); try { execFileSync(cli, args, { stdio: ['ignore', 'pipe', 'pipe'], maxBuffer: 1 << 30 }); } catch (e) { return `failed: ${String(e.stderr).trim()}`; } return `${(Number(process.hrtime.bigint() - t) / 1e6).toFixed(0)} ms`; };
  const tmp = fs.mkdtempSync('/tmp/tristim-bench-');
  console.log('native CLI (same work):');
  console.log(`  sample the DNG: ${time(['sample', DNG, '--chart', 'passport', '--corners', example.corners.join(',')])}`);
  try {
    fs.writeFileSync(path.join(tmp, 'rgb.csv'), execFileSync(cli, ['sample', DNG, '--chart', 'passport', '--corners', example.corners.join(',')]));
    fs.writeFileSync(path.join(tmp, 'xyz.csv'), execFileSync(cli, ['reference', '--chart', 'passport', '--illuminant', 'D50']));
    for (const m of ['matrix-3x3', 'Finlayson2015-2', 'Shen2008']) {
      console.log(`  fit ${m}: ${time(['fit', '--rgb', path.join(tmp, 'rgb.csv'), '--xyz', path.join(tmp, 'xyz.csv'), '--model', m, '--out', path.join(tmp, `${m}.json`)])}`);
    }
    const applied = time(['apply', path.join(tmp, 'Finlayson2015-2.json'), CR2, '--out', path.join(tmp, 'xyz.pfm')]);
    console.log(`  apply Finlayson2015-2 to the CR2: ${applied.startsWith('failed') ? 'n/a (this CLI applies profiles to PFM images, not RAW files)' : applied}`);
    console.log(`  inspect the CR2 (metadata only): ${time(['inspect', CR2])}`);
  } catch (e) { console.log(`  (native pipeline incomplete: ${String(e.stderr ?? e.message).trim().split('\n')[0]})`); }
  fs.rmSync(tmp, { recursive: true, force: true });
} else console.log('native CLI not built (build/native/core/tristim): no native figures');

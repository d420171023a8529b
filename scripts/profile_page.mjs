// Where the page's time goes (issue 13): runs one journey of tests/web/bench_journey.mjs in headless
// Chromium on an instrumented copy of the site and prints a timeline, in ms from the journey's start:
//   - every message the page sends to a worker and every reply (p0 = the engine's worker, p1… = the
//     compare's pool), new workers, long tasks of the page's main thread (> 50 ms), performance marks;
//   - in each worker: when it started running its code (its module graph loaded), when the wasm
//     module was instantiated, and for every request when it arrived, started and ended (model and
//     objective for a fit);
//   - per pool worker: rows, time running fits, idle gaps between rows, and the longest rows.
// Journeys: first (a new session's first screen, the module cached), dng (the Passport DNG dropped,
// then every row compared), cr2 (the Canon CR2 chosen in step 5, its Y map drawn).
// usage: node scripts/profile_page.mjs [first|dng|cr2] [--reps N] [--site DIR] [--trace FILE] [--node]
//   --site: the built site (default build/wasm/site); it is copied to a temporary folder and its
//           worker.js instrumented (the site itself is left as is).
//   --trace: also writes a Chromium trace (chrome://tracing, Perfetto) of the last repetition.
//   --node: replays the last repetition's fit requests, one after the other, through the same
//           site's worker handler (web/fit/handlers.js, the same tristim.mjs/.wasm) under node, three
//           times: what the rows cost in wasm on one thread with nothing else running, next to the
//           pool workers' time (the difference is the page sharing the cores: its own thread, the
//           other worker, Chromium's threads).
// Figures are wall-clock times: on a busy machine say the load (printed) next to them, and compare
// two sites by alternating runs (A, B, A, B) rather than against figures taken at another time.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { parseArgs } from 'node:util';
import { fileURLToPath } from 'node:url';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const { values: opt, positionals } = parseArgs({
  allowPositionals: true,
  options: { reps: { type: 'string', default: '1' }, site: { type: 'string' }, trace: { type: 'string' }, node: { type: 'boolean', default: false } },
});
const journey = positionals[0] ?? 'first';
if (!['first', 'dng', 'cr2'].includes(journey)) throw new Error(`unknown journey '${journey}' (first, dng or cr2)`);

// An instrumented copy of the site: the worker logs its start, the module's instantiation and each
// request (absolute times, so page and workers share one clock) on the console as PROF {json}.
const site = path.resolve(opt.site ?? path.join(repo, 'build/wasm/site'));
const copy = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-profile-'));
fs.cpSync(site, copy, { recursive: true });
const workerJs = path.join(copy, 'worker.js');
let w = fs.readFileSync(workerJs, 'utf8');
const patch = (from, to) => { if (!w.includes(from)) throw new Error(`worker.js changed: cannot instrument at '${from.trim()}'`); w = w.replace(from, to); };
patch("self.onmessage = async (ev) => {\n  const msg = ev.data;",
  "self.onmessage = async (ev) => {\n  const msg = ev.data;\n  const __t0 = __abs();\n"
  + "  if (msg.type === 'module') engine().then(() => __log({ ev: 'instantiated', t: __abs() }));"
  + (opt.node ? "\n  if (msg.type === 'fit') __log({ ev: 'request', t: __t0, msg: JSON.stringify(msg, (k, v) => (ArrayBuffer.isView(v) ? { __typed: v.constructor.name, v: Array.from(v) } : v)) });" : ''));
patch('    const out = await handler(T, msg, { state, progress });',
  '    const __t1 = __abs();\n    const out = await handler(T, msg, { state, progress });\n'
  + '    __log({ ev: msg.type, id: msg.id, recv: __t0, start: __t1, end: __abs(), model: msg.recipe?.characterisation?.model, obj: msg.recipe?.characterisation?.objective?.method });');
w = "const __abs = () => performance.timeOrigin + performance.now();\nconst __wid = Math.random().toString(36).slice(2, 6);\n"
  + "const __log = (e) => console.log('PROF ' + JSON.stringify({ w: __wid, ...e }));\n__log({ ev: 'worker-start', t: __abs() });\n" + w;
fs.writeFileSync(workerJs, w);
process.env.TRISTIM_SITE_DIR = copy;   // read by the harness when it is imported

const { openBrowser } = await import('../tests/web/harness.mjs');
const { step, upload, fileBuffer, waitReady, DNG, CR2 } = await import('../tests/web/journey.mjs');
const example = JSON.parse(fs.readFileSync(path.join(repo, 'examples/web/passport.json'), 'utf8'));

const b = await openBrowser();
const { page } = b;
const logs = [];
page.on('console', (m) => { const s = m.text(); if (s.startsWith('PROF ')) logs.push(JSON.parse(s.slice(5))); });
// The page side: workers created, messages sent and replies, long tasks, marks.
await page.addInitScript(() => {
  const abs = () => performance.timeOrigin + performance.now();
  const log = (e) => console.log('PROF ' + JSON.stringify(e));
  const W = window.Worker;
  let n = 0;
  window.Worker = class extends W {
    constructor(u, o) {
      super(u, o);
      this.__n = n++;
      log({ p: this.__n, ev: 'new-worker', t: abs() });
      this.addEventListener('message', (e) => { if (e.data?.type !== 'progress') log({ p: this.__n, ev: 'reply', id: e.data?.id, t: abs() }); });
    }
    postMessage(m, t) { log({ p: this.__n, ev: `send:${m?.type}`, id: m?.id, t: abs() }); return super.postMessage(m, t); }
  };
  new PerformanceObserver((l) => { for (const e of l.getEntries()) log({ ev: 'longtask', t: performance.timeOrigin + e.startTime, dur: e.duration }); }).observe({ type: 'longtask', buffered: true });
  new PerformanceObserver((l) => { for (const e of l.getEntries()) log({ ev: `mark:${e.name}`, t: performance.timeOrigin + e.startTime }); }).observe({ type: 'mark', buffered: true });
});

async function withTrace(last, fn) {
  if (!opt.trace || !last) return fn();
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Tracing.start', { transferMode: 'ReturnAsStream',
    categories: 'devtools.timeline,v8.execute,disabled-by-default-devtools.timeline,disabled-by-default-v8.cpu_profiler,blink.user_timing,v8' });
  const out = await fn();
  const done = new Promise((r) => cdp.once('Tracing.tracingComplete', r));
  await cdp.send('Tracing.end');
  const { stream } = await done;
  const parts = [];
  for (;;) { const c = await cdp.send('IO.read', { handle: stream }); parts.push(c.data); if (c.eof) break; }
  fs.writeFileSync(opt.trace, parts.join(''));
  return out;
}

/// Runs the journey once; returns the absolute time it started at.
async function runOnce(last) {
  const armAt = (q) => page.evaluate((sel) => {
    document.querySelector(sel).addEventListener('change', () => { window.__t0 = performance.timeOrigin + performance.now(); }, { capture: true, once: true });
  }, q);
  if (journey === 'first') {
    await page.evaluate(() => window.tristim.store.clear());
    logs.length = 0;
    await withTrace(last, async () => { await page.reload(); await waitReady(page, 120000); });
    return page.evaluate(() => performance.timeOrigin);
  }
  if (journey === 'dng') {
    await step(page, 'images');
    await page.evaluate((cs) => window.tristim.save('corners', cs), example.corners);
    await armAt('#step-images input[data-slot="chart"]');
    await page.evaluate(() => { window.__oldSample = window.tristim.derived.sample; });
    logs.length = 0;
    await withTrace(last, async () => {
      await upload(page, '#step-images input[data-slot="chart"]', 'passport-p.dng', fileBuffer(DNG));
      await page.waitForFunction(() => window.tristim.derived.sample && window.tristim.derived.sample !== window.__oldSample, null, { timeout: 60000 });
      // (returns nothing: the results handed back to node would be serialised on the page's thread)
      await page.evaluate(async () => { await window.tristim.views.fit.run({ onFirst: () => window.tristim.goto('results') }); });
    });
  } else {
    await step(page, 'apply');
    await page.selectOption('#step-apply select >> nth=0', 'scene');
    await armAt('#step-apply input[type=file]');
    logs.length = 0;
    await withTrace(last, async () => {
      await upload(page, '#step-apply input[type=file]', 'scene-p.CR2', fileBuffer(CR2));
      await page.evaluate(() => window.tristim.views.apply.run());
      await page.waitForSelector('#step-apply .legend-box');
    });
  }
  return page.evaluate(() => window.__t0);
}

function report(t0, end) {
  console.log(`--- ${journey}: ${(end - t0).toFixed(0)} ms from the start to the end of the journey (load average ${os.loadavg().map((x) => x.toFixed(2)).join(', ')})`);
  const rel = (t) => (t - t0).toFixed(0).padStart(6);
  for (const e of [...logs].sort((x, y) => (x.recv ?? x.t) - (y.recv ?? y.t))) {
    if (e.start) console.log(`${rel(e.recv)} w${e.w} ${e.ev}#${e.id} queued ${(e.start - e.recv).toFixed(0)} ran ${(e.end - e.start).toFixed(0)} -> ${rel(e.end)} ${e.model ?? ''} ${e.obj ?? ''}`);
    else console.log(`${rel(e.t)} ${e.w ? `w${e.w}` : e.p !== undefined ? `p${e.p}` : '  '} ${e.ev}${e.id ? `#${e.id}` : ''}${e.dur ? ` ${e.dur.toFixed(0)} ms` : ''}`);
  }
  // Per worker that fitted: rows, busy time, idle gaps between its rows, and the longest rows.
  const fits = logs.filter((e) => e.ev === 'fit' && e.start);
  const byWorker = Map.groupBy ? Map.groupBy(fits, (e) => e.w) : fits.reduce((m, e) => m.set(e.w, [...(m.get(e.w) ?? []), e]), new Map());
  for (const [wid, rows] of byWorker) {
    rows.sort((x, y) => x.start - y.start);
    const ran = rows.reduce((a, r) => a + r.end - r.start, 0);
    let idle = 0;
    for (let i = 1; i < rows.length; i++) idle += Math.max(0, rows[i].start - rows[i - 1].end);
    console.log(`  w${wid}: ${rows.length} rows, running ${ran.toFixed(0)} ms from ${rel(rows[0].start).trim()} to ${rel(rows.at(-1).end).trim()}, idle between rows ${idle.toFixed(0)} ms`);
  }
  const longest = [...fits].sort((x, y) => (y.end - y.start) - (x.end - x.start)).slice(0, 8);
  if (longest.length) console.log(`  longest rows: ${longest.map((r) => `${r.model} ${r.obj} ${(r.end - r.start).toFixed(0)}`).join(', ')}`);
}

/// The fit requests the page sent (in the order they arrived at the workers), through the site's
/// own fit handler under node on one thread, three times; prints the total and the longest rows,
/// next to the page's workers.
async function replayInNode(requests) {
  if (!requests.length) { console.log('--node: this journey sent no fit request'); return; }
  const revive = (k, v) => (v && v.__typed ? new globalThis[v.__typed](v.v) : v);
  const msgs = requests.sort((a, b) => a.t - b.t).map((e) => JSON.parse(e.msg, revive));
  const { default: createTristim } = await import(path.join(copy, 'tristim.mjs'));
  const { handlers } = await import(path.join(copy, 'fit/handlers.js'));
  const T = await createTristim();
  const fits = logs.filter((e) => e.ev === 'fit' && e.start);
  const inPage = fits.reduce((a, r) => a + r.end - r.start, 0);
  console.log(`--- node ${process.version}, one thread, the same ${msgs.length} fit requests through the site's fit handler (web/fit/handlers.js)`
    + ` (the page's workers: ${inPage.toFixed(0)} ms running them, over ${new Set(fits.map((r) => r.w)).size} workers)`);
  for (let rep = 1; rep <= 3; rep++) {
    let total = 0, refused = 0;
    const rows = [];
    for (const m of msgs) {
      const msg = structuredClone(m);
      const t = performance.now();
      try { handlers.fit(T, msg, { progress: () => {} }); } catch { refused++; }
      const dt = performance.now() - t;
      total += dt;
      rows.push([`${msg.recipe.characterisation.model} ${msg.recipe.characterisation.objective.method}`, dt]);
    }
    rows.sort((a, b) => b[1] - a[1]);
    console.log(`  run ${rep}: ${total.toFixed(0)} ms (${refused} refused); longest ${rows.slice(0, 4).map(([n, d]) => `${n} ${d.toFixed(0)}`).join(', ')}`);
  }
}

try {
  await page.goto(`${b.origin}/`);
  await waitReady(page, 120000);
  const reps = Math.max(1, Number(opt.reps));
  for (let k = 0; k < reps; k++) {
    const t0 = await runOnce(k === reps - 1);
    const end = await page.evaluate(() => performance.timeOrigin + performance.now());
    report(t0, end);
  }
  if (b.problems.length) console.log('problems:', b.problems);
  if (opt.node) await replayInNode(logs.filter((e) => e.ev === 'request'));
} finally {
  await b.close();
  fs.rmSync(copy, { recursive: true, force: true });
}

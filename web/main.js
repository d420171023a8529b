// Page entry: starts the engine in a worker, restores the session from IndexedDB (or loads the
// example chart on a first visit), and mounts one view per step of the journey.
import { Engine } from './lib/engine.js';
import { store } from './store.js';
import { h } from './lib/ui.js';
import { fetchExample, decodeExample } from './images/example.js';

// The engine's worker, the compile of the wasm module and (a new session) the example's fetch and
// decode were started by boot.js before this module graph loaded; the Engine takes that worker
// over. Without boot.js (it failed), they start here. The views and their plots load meanwhile.
const boot = self.tristimBoot ?? null;
delete self.tristimBoot;   // taken over once (a restarted engine starts a new worker)
const engine = new Engine({ boot });
// read while the engine starts (a fresh session loads the example)
const storedSession = store.all().catch((e) => { console.warn(`session storage unavailable: ${e.message}`); return {}; });

// The features, in journey order: web/<feature>/view.js, each mounted into <section id="step-<feature>">.
const STEPS = ['reference', 'surface', 'images', 'linearisation', 'fit', 'results', 'apply', 'export', 'absolute', 'lab', 'share'];
const FEATURES = Promise.all(STEPS.map((s) => import(`./${s}/view.js`)))
  .then((mods) => Object.fromEntries(STEPS.map((s, i) => [s, mods[i]])));
FEATURES.catch(() => {});   // a failed load is reported by start()
const status = document.getElementById('engine-status');

const app = {
  engine,
  store,
  session: {},        // persisted: settings, surface, surfaceSettings, surfaceCompare, linearisation, linearisationSettings, files.*, corners, layout, fitChoice, results (each with its recipe), selected, recipe, step
  derived: {},        // recomputed: reference, locus, sample, preview
  views: {},
  bus: new EventTarget(),
  on(topic, fn) { this.bus.addEventListener(topic, (e) => fn(e.detail)); },
  emit(topic, detail) { this.bus.dispatchEvent(new CustomEvent(topic, { detail })); },
  /// Keeps session[key] and writes it to IndexedDB (errors are reported, never thrown).
  async save(key, value) {
    this.session[key] = value;
    try {
      if (value === undefined) await store.delete(key); else await store.set(key, value);
    } catch (e) { console.warn(`could not keep ${key} in this browser's storage: ${e.message}`); }
  },
  goto(step, { focus = false } = {}) {
    if (!STEPS.includes(step)) step = 'reference';
    for (const s of document.querySelectorAll('main > section')) s.hidden = s.dataset.step !== step;
    for (const a of document.querySelectorAll('#steps a')) {
      if (a.dataset.step === step) a.setAttribute('aria-current', 'step'); else a.removeAttribute('aria-current');
    }
    document.body.dataset.step = step;
    if (this.session.step !== step) this.save('step', step);
    this.emit('step', step);
    if (focus) document.getElementById(`h-${step}`)?.focus();
  },
  /// Marks a step in the navigation as done/ready (a small tick, text for screen readers).
  mark(step, state) {
    const a = document.querySelector(`#steps a[data-step="${step}"]`);
    if (a) a.dataset.state = state;
  },
};
window.tristim = app;   // for tests and the curious

// The worker died (engine.js recover): a new one is already running; say what happened.
app.engine.addEventListener('crashed', (e) => {
  status.textContent = `The colour engine stopped (${e.detail}) and was restarted; your files, corners and results are kept. ` +
    'If a step shows an error, run it again.';
  status.classList.add('error');
  status.dataset.crashes = String(app.engine.crashes);
});

for (const a of document.querySelectorAll('#steps a')) {
  a.addEventListener('click', (e) => { e.preventDefault(); app.goto(a.dataset.step, { focus: true }); history.replaceState(null, '', `#${a.dataset.step}`); });
}
for (const s of STEPS) document.getElementById(`h-${s}`).tabIndex = -1;

document.getElementById('new-session').addEventListener('click', async () => {
  if (!confirm('Start a new session? Every file, corner, setting and result kept in this browser is forgotten.')) return;
  await store.clear();
  location.hash = '';
  location.reload();
});

async function start() {
  // The worker answers in the order asked: hello, the catalog, then (a new session) the example's
  // decode — all asked by boot.js before this module loaded; the decode runs while the views load
  // and mount.
  const hello = boot?.hello ?? app.engine.call('hello'), catalog = boot?.catalog ?? app.engine.call('catalog');
  // A new session loads the example: boot.js's (its decode already queued), or fetched now and its
  // decode queued as soon as it is here (boot.js missing, or its fetch failed).
  const example = storedSession.then(async (s) => (s.settings ? null
    : (await boot?.example.catch(() => null)) ?? decodeExample(app.engine, await fetchExample())));
  for (const p of [hello, catalog, example]) p.catch(() => {});   // reported below / by the images view
  try {
    const { version } = await hello;
    app.catalog = await catalog;
    status.textContent = `Colour engine tristim ${version} ready (WebAssembly, in a worker).`;
    status.dataset.ready = 'true';
  } catch (e) {
    status.textContent = `The colour engine failed to start: ${e.message} (${e.code}).`;
    status.classList.add('error');
    return;
  }
  const saved = await storedSession;
  const fresh = !saved.settings;
  Object.assign(app.session, saved);
  // Results kept by a page from before a recipe crossed as its JSON (a layout's margin_left …, no
  // `margins`): each one's recipe as its profile embeds it, the form the engine reads.
  for (const r of app.session.results ?? []) {
    if (!r.recipe?.sampling?.layout || r.recipe.sampling.layout.margins || !r.fit?.profile) continue;
    const { format, ...recipe } = JSON.parse(r.fit.profile).recipe;
    r.recipe = r.fit.recipe = recipe;
    if (r.key === app.session.selected) app.session.recipe = recipe;
  }

  const features = await FEATURES;
  // The plotting library (deferred scripts) has run once the document is parsed.
  if (document.readyState === 'loading') await new Promise((r) => document.addEventListener('DOMContentLoaded', r, { once: true }));
  for (const [step, mod] of Object.entries(features)) {
    app.views[step] = mod.mount(document.getElementById(`step-${step}`), app);
  }
  if (fresh) await app.save('settings', { ...app.session.settings });   // the session now exists
  const hash = location.hash.slice(1);
  app.goto(STEPS.includes(hash) ? hash : (app.session.step ?? (fresh ? 'results' : 'reference')));
  app.views.share.openFromHash();   // a shared link (#tristim=…): recomputed, the session untouched
  app.views.lab?.openFromHash?.();   // a lab set-up link (#lab=…): the exercise's tab, set and run

  // Restore (or, on a first visit, load the example): the chart's sampling does not wait for the
  // reference's plots (both are needed before the fit).
  if (fresh) app.views.results.setStatus('Loading the example: a ColorChecker Passport photographed as DNG, decoding and sampling it in the worker…');
  // A new session: the example's write to storage waits for the first screen; its preview and its
  // detection (a proposal: its corners are preset) for the compare's end — on two cores they would
  // slow the compare (the first screen shows the results step, not the picture).
  let shown = null, compared = null;
  const firstScreen = fresh ? new Promise((r) => { shown = r; }) : null;
  const compareDone = fresh ? new Promise((r) => { compared = r; }) : null;
  const restored = app.views.images.restore(fresh, { detectAfter: compareDone, storeAfter: firstScreen, example: fresh ? example : null });
  await app.views.reference.ready;
  await restored;
  if (fresh) {
    app.views.results.setStatus('Fitting the example: every model × objective, the first one shown as soon as it is in…');
    const r = await app.views.fit.runDefault({ onFirst: () => { performance.mark('tristim:first-screen'); document.body.dataset.firstScreen = 'true'; shown(); } });
    shown();
    compared();
    if (!r) app.views.results.setStatus('No fitted model yet: the example could not be fitted (see steps 1–3).');
  } else app.views.results.refresh();
  performance.mark('tristim:ready');
  document.body.dataset.ready = 'true';
}

start().catch((e) => {
  status.textContent = `The page failed to start: ${e.message} (${e.code ?? 'INTERNAL'}).`;
  status.classList.add('error');
  document.body.append(h('pre', { class: 'error' }, String(e.stack ?? e)));
});

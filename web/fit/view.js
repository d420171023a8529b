// Step 3: pick any number of models x objectives (all of them by default: compare everything) and
// fit them in a few workers side by side, with progress, a cancel button (which terminates those
// workers) and the rows streaming into the results as each finishes.
import { h, field, showError, clearError, progressBar, readText } from '../lib/ui.js';
import { pairData, excludeFlags, heldOutSet } from '../lib/pairs.js';
import { metric } from '../lib/metrics.js';
import { optionsForm, completeChoice } from '../lib/options_form.js';
import { WorkerPool } from './pool.js';
import { withImages, chartsOf, extraCharts } from '../images/second.js';

export function mount(section, app) {
  const { engine } = app;
  const models = app.catalog.models;           // the engine's model table (ModelInfo rows, each naming its family)
  const families = app.catalog.modelFamilies;  // the engine's model families, in the table's order
  const objectives = app.catalog.objectives;   // the engine's objective table (MethodInfo rows)
  const choice = (app.session.fitChoice ??= defaultChoice(models, objectives));
  // Each objective's options as a MethodChoice, completed from the table's defaults.
  choice.objectiveChoices = Object.fromEntries(objectives.map((o) => [o.id, completeChoice(o, choice.objectiveChoices?.[o.id])]));

  const modelBox = h('fieldset', { class: 'checklist' }, h('legend', {}, 'Models'));
  for (const fam of families) {
    const group = h('div', { class: 'family', dataset: { family: fam.id } }, h('h4', {}, fam.label));
    if (fam.about) group.append(h('small', { class: 'hint' }, fam.about));
    for (const m of models.filter((x) => x.family === fam.id)) {
      const cb = h('input', { type: 'checkbox', value: m.id, checked: choice.models.includes(m.id), dataset: { model: m.id } });
      cb.id = `model-${m.id}`;
      cb.addEventListener('change', () => { toggle(choice.models, m.id, cb.checked); persist(); });
      group.append(h('div', { class: 'check', title: m.reference }, cb, h('label', { for: cb.id }, m.label),
        h('code', { class: 'model-id' }, m.id), m.duplicate_of ? h('small', { class: 'hint' }, `same span as ${m.duplicate_of}`) : null));
    }
    modelBox.append(group);
  }
  const objBox = h('fieldset', { class: 'checklist' }, h('legend', {}, 'Objectives'));
  for (const o of objectives) {
    const cb = h('input', { type: 'checkbox', value: o.id, checked: choice.objectives.includes(o.id), dataset: { objective: o.id } });
    cb.id = `objective-${o.id}`;
    cb.addEventListener('change', () => { toggle(choice.objectives, o.id, cb.checked); persist(); });
    objBox.append(h('div', { class: 'check' }, cb, h('label', { for: cb.id }, o.label), o.reference ? h('small', { class: 'hint' }, ` ${o.reference}`) : null));
    if (o.options.length) {
      objBox.append(h('details', { class: 'objective-options', dataset: { objective: o.id } }, h('summary', {}, `${o.label}: options`),
        h('div', { class: 'controls' }, optionsForm(o, choice.objectiveChoices[o.id], () => persist()))));
    }
  }
  // The sample flags a fit may leave out: one toggle per row of the engine's table (label, default);
  // the recipe's sampling.exclude_flags lists those checked and the engine leaves the patches out.
  // "Every flag" checks them all; unchecked, the table's defaults again.
  const flagRows = app.catalog.sampleFlags;
  choice.excludeFlags = excludeFlags(choice, flagRows);
  const flagBoxes = flagRows.map((f) => h('input', { type: 'checkbox', id: `exclude-${f.name}`, value: f.name, checked: choice.excludeFlags.includes(f.name), dataset: { flag: f.name } }));
  const excludeAllCb = h('input', { type: 'checkbox', id: 'exclude-flagged' });
  const setFlags = (names) => {
    choice.excludeFlags = flagRows.map((f) => f.name).filter((n) => names.includes(n));
    for (const cb of flagBoxes) cb.checked = choice.excludeFlags.includes(cb.value);
    excludeAllCb.checked = choice.excludeFlags.length === flagRows.length;
    persist();
    describeData();
  };
  for (const cb of flagBoxes) cb.addEventListener('change', () => setFlags(flagBoxes.filter((b) => b.checked).map((b) => b.value)));
  excludeAllCb.addEventListener('change', () => setFlags(excludeAllCb.checked ? flagRows.map((f) => f.name) : excludeFlags({}, flagRows)));
  excludeAllCb.checked = choice.excludeFlags.length === flagRows.length;
  const whiteCb = h('input', { type: 'checkbox', checked: !!choice.preserveWhite });
  whiteCb.addEventListener('change', () => { choice.preserveWhite = whiteCb.checked; persist(); });
  const heldInput = h('input', { type: 'file', accept: '.csv,.txt,.ti3,.cgats' });
  const heldState = h('span', { class: 'file-state' });
  const heldClear = h('button', { type: 'button', hidden: true }, 'Remove');
  const heldField = field('Held-out chart (optional): camera RGB per patch, CSV or CGATS', heldInput,
    'Another photograph or chart, e.g. the CSV of `tristim sample`. Its X, Y, Z columns are used when present, otherwise its ids are paired with the reference. Every fit is also evaluated on it.');
  const runBtn = h('button', { type: 'button', class: 'primary' }, 'Fit and compare the selected');
  const cancelBtn = h('button', { type: 'button', class: 'cancel', disabled: true }, 'Cancel');
  const progress = progressBar('Fitting');
  const log = h('ul', { class: 'fit-log', 'aria-live': 'polite' });
  const dataNote = h('p', { class: 'summary' });

  section.append(dataNote, h('div', { class: 'fit-choice' }, modelBox, objBox),
    h('div', { class: 'controls' },
      ...flagRows.map((f, i) => h('div', { class: 'check', title: f.description }, flagBoxes[i], h('label', { for: flagBoxes[i].id }, f.label))),
      h('div', { class: 'check' }, excludeAllCb, h('label', { for: excludeAllCb.id }, 'Leave out every flagged patch')),
      h('div', { class: 'check' }, whiteCb, h('label', { for: whiteCb.id = 'preserve-white' }, 'Preserve the white: the fit maps the brightest patch (the chart\'s white) exactly'))),
    h('div', { class: 'controls' }, h('div', { class: 'field-group' }, heldField, heldState, heldClear)),
    h('div', { class: 'controls' }, runBtn, cancelBtn), progress.el, log);
  runBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'fit-error' });
  runBtn.setAttribute('aria-describedby', 'fit-error');
  runBtn.after(cancelBtn, runBtn._errorSlot);

  const persist = () => app.save('fitChoice', JSON.parse(JSON.stringify(choice)));

  /// The patches paired as the fit pairs them (the engine's pairing, lib/pairs.js, with the
  /// recipe's sampling.exclude_flags); {error} when the engine refuses the pairing.
  let described = 0;
  async function describeData() {
    const mine = ++described;
    const s = app.derived.sample, r = app.derived.reference;
    if (!s || !r) { dataNote.textContent = 'Fitting needs a reference (step 1) and a sampled chart (step 2).'; return null; }
    let d;
    try {
      d = await pairData(engine, s, r, { exclude_flags: choice.excludeFlags });
    } catch (error) {
      if (mine === described) dataNote.textContent = `The sampled chart does not pair with the reference: ${error.message}.`;
      return { error };
    }
    if (mine !== described) return d;
    // the engine's left-out lines ("A3 (saturated)"), those of the patches outside the frame last
    const extra = extraCharts(app);
    const outside = s.missing ?? [], flagged = d.excluded.slice(0, d.excluded.length - outside.length);
    const surface = app.session.surface, corrected = surface && surface.method !== 'none' && !r.settings.referenceFile;
    dataNote.textContent = `${d.ids.length} patches pair sampled RGB with reference XYZ`
      + (corrected ? ` (the reference corrected for the capture geometry: ${surface.method}, step 1b)` : '')
      + linearisationText(app.session.linearisation, app.derived.image?.metadata)
      + (flagged.length ? `; left out: ${flagged.join(', ')}` : '')
      + (outside.length ? `; outside the frame (not sampled): ${outside.join(', ')}` : '')
      + (extra.count ? `; and the ${extra.patches} patches of ${extra.count === 1 ? 'the second chart image' : `chart images 2–${extra.count + 1}`} (${extra.names}, step 2): one fit on ${extra.count === 1 ? 'both' : 'all'}` : '') + '.';
    return d;
  }
  app.on('sample2', describeData);
  app.on('sample', describeData);
  app.on('reference', describeData);
  app.on('surface', describeData);
  app.on('linearisation', describeData);

  let heldOut = null;
  async function setHeldOut(file) {
    clearError(heldInput);
    try {
      heldOut = file ? await heldOutSet(engine, file, app.derived.reference) : null;
      const without = heldOut?.withoutRGB ?? [];
      heldState.textContent = heldOut ? `${heldOut.name}: ${heldOut.ids.length} patches held out`
        + (without.length ? ` (${without.length} reference patches have no RGB: ${without.join(', ')}).` : '.') : '';
      heldClear.hidden = !heldOut;
      await app.save('heldOutFile', file ?? undefined);
    } catch (e) { showError(heldInput, e, file.name); }
  }
  heldInput.addEventListener('change', async () => {
    const f = heldInput.files[0];
    const text = f && await readText(heldInput, f);
    if (text != null) await setHeldOut({ name: f.name, text });
  });
  heldClear.addEventListener('click', () => { heldInput.value = ''; setHeldOut(null); });
  if (app.session.heldOutFile) app.on('reference', function once() { if (!heldOut) setHeldOut(app.session.heldOutFile); });

  // The rows run in a few workers of their own (pool.js), side by side; the engine's worker, which
  // keeps the decoded images, is left alone, so Cancel stops the rows and nothing else.
  const pool = new WorkerPool(Math.max(2, Math.min(8, navigator.hardwareConcurrency || 2)), {
    onCrash: (reason) => {   // said on the page's status line, as for the engine's own worker
      engine.crashes++;
      engine.dispatchEvent(new CustomEvent('crashed', { detail: reason }));
    },
  });
  // The pool's workers start with the first compare (map() warms them), not here: on a new
  // session's first screen that is once the first row (fitted in the engine's worker) is plotted.
  // Started at mount, their module graphs and instances competed with the example's decode for
  // the cores: the first screen's first row 920–930 ms → 770–800 (median of 3, twice, on a 2-core
  // VM), every row no later.
  const nTerms = new Map(app.catalog.models.map((m) => [m.id, m.n_terms]));
  let running = false;
  cancelBtn.addEventListener('click', () => {
    if (!running) return;
    pool.stop();   // the workers are terminated: the rows in flight stop now
  });

  /// Fits every selected model x objective (each row with leave-one-out), spread over the pool's
  /// workers; rows stream into the results as each one finishes. `onFirst()` runs once the first
  /// row is in (the results step then shows it while the others run). `firstOnEngine`: the first
  /// row runs in the engine's own worker (warm, idle after the sampling) while the pool's workers
  /// start. Returns the results (also kept in the session), the rows finished so far when
  /// cancelled, or null.
  async function run({ onFirst, firstOnEngine = false } = {}) {
    clearError(runBtn);
    log.replaceChildren();   // the last run's lines go now: the pairing below is asynchronous
    runBtn.disabled = true;
    const data = await describeData();
    runBtn.disabled = false;
    if (!data) { showError(runBtn, new Error('no paired data yet: set the reference and sample the chart first'), 'Fit'); return null; }
    if (data.error) {
      const e = data.error, advice = e.code === 'PATCH_MISMATCH' ? ': choose the chart layout or reference that belong together' : '';
      showError(runBtn, Object.assign(new Error(`${e.message}${advice}`), { code: e.code }), 'Fit');
      return null;
    }
    const objectiveIds = objectives.map((o) => o.id).filter((id) => choice.objectives.includes(id));
    const jobs = rowOrder(choice.models, objectiveIds, nTerms);
    // The rows run longest first (rowOrder), and finish in any order; the log lists them as the
    // models and objectives are listed above (model by model), whatever order they finish in.
    const listed = families.flatMap((fam) => models.filter((x) => x.family === fam.id).map((x) => x.id));
    const readingOrder = new Map(listed.flatMap((m, i) => objectiveIds.map((o, k) => [`${m}|${o}`, i * objectiveIds.length + k])));
    const logRow = (job, li) => {
      const n = readingOrder.get(`${job.mId}|${job.obj}`) ?? Infinity;
      Object.assign(li.dataset, { order: n, model: job.mId, objective: job.obj });
      log.insertBefore(li, [...log.children].find((x) => Number(x.dataset.order) > n) ?? null);
    };
    if (!jobs.length) { showError(runBtn, Object.assign(new Error('choose at least one model and one objective'), { code: 'NOTHING_SELECTED' }), 'Fit'); return null; }
    running = true; runBtn.disabled = true; cancelBtn.disabled = false;
    const total = jobs.length;
    const say = (done) => {
      progress.update({ fraction: done / total, stage: `${done} of ${total} rows (model × objective, each with leave-one-out) on ${pool.size} workers` });
      app.emit('compare', { done, total, running });
    };
    progress.start('Fitting…');
    say(0);
    log.replaceChildren();
    const results = [];
    const ref = app.derived.reference;
    const { source, settings, data_digest, ...reference } = ref;   // the engine's ReferenceChart
    const { layout, homography, patches, missing = [] } = app.derived.sample;     // the engine's ChartSample
    const sample = { layout, homography, patches, missing };   // a cut chart's missing patches: in the profile's recipe
    const t0 = performance.now();
    let done = 0, autoKey = null, frame = 0, lastDraw = 0, shownFirst = null;
    // The page draws what the arriving rows change — the results table, the rows' log lines, the
    // progress — at most every 250 ms (in an animation frame), not once per row: each redraw
    // (layout, paint) takes the page a few ms of a core the workers need, the table's ~50 ms. On a
    // 2-core machine the per-row log and progress updates alone (48 rows, ~90 paints) cost the
    // compare 0.2–0.3 s (Chromium trace of the DNG journey, scripts/profile_page.mjs).
    const pendingLog = [];   // [job, li] of rows ended since the last redraw
    const flush = () => {
      for (const [job, li] of pendingLog.splice(0)) logRow(job, li);
      say(done);
    };
    const stream = () => {
      frame ||= setTimeout(() => requestAnimationFrame(() => {
        if (!frame) return;
        frame = 0; lastDraw = performance.now();
        flush();
        if (autoKey) app.emit('results', results);
      }), Math.max(0, lastDraw + 250 - performance.now()));
    };
    try {
      const task = async (client, job) => {
        // a second chart image: both (its entry takes the recipe's exclude_flags, the engine applies them)
        job.recipe = await withImages(app, recipeFor(job.mId, job.obj, ref, data));
        return client.call('fit', { recipe: job.recipe, sample, reference, heldOut, charts: chartsOf(app, job.recipe, sample, reference) });
      };
      const onRow = (job, { result: fit, error }) => {
        const { mId, obj, recipe } = job;
        done++;
        const m = models.find((x) => x.id === mId) ?? { label: mId };
        // A fitted row names its objective as it ran (the engine's objectiveChoiceLabel: for
        // CIEDE2000 the loss and the optimiser); a refused one by its table row.
        const label = `${m.label} · ${fit?.objective_label ?? objectives.find((o) => o.id === obj)?.label ?? obj}`;
        if (error) {
          pendingLog.push([job, h('li', { class: 'error', dataset: { code: error.code } }, `${label}: ${error.message} (${error.code})`)]);
        } else {
          results.push({ key: `${mId}|${obj}|${JSON.stringify(recipe.characterisation.objective)}`, modelId: mId, objective: obj, label,
            recipe: fit.recipe, white: fit.recipe.characterisation.lab_white, ids: fit.ids, labels: fit.labels, rgb: fit.linear_RGB, xyz: fit.reference_XYZ,
            fit, heldOut: fit.held_out ?? null, referenceText: referenceText(ref), camera: cameraOf(app.derived.image?.metadata) });
          const { status, message } = fit.evaluation.fit;
          const joint = jointSurface(recipe.surface, ref.settings) ? `; surface fitted jointly (Phase II): ${choiceText(fit.surface)} (${fit.surface_status})` : '';
          const mu = fit.evaluation.fit.mu ? `; white scaling μ = ${fit.evaluation.fit.mu.toFixed(4)} (Abed 2013 eq 27)` : '';  // corrected-3x3
          pendingLog.push([job, h('li', {}, `${label}: done in ${fit.worker_ms.toFixed(0)} ms${status !== 'ok' ? ` — ${status}: ${message}` : ''}${joint}${mu}`)]);
        }
        // The first job's row (the default model) replaces the previous results and is shown; rows
        // that end before it wait for it (or for its error), so the first plots are the default's.
        const row = error ? null : results[results.length - 1];
        if (!autoKey && (job === jobs[0] || shownFirst === false) && results.length) {
          app.session.results = results;
          app.session.selected = autoKey = (row && job === jobs[0] ? row : results[0]).key;
          flush();
          app.emit('results', results);
          onFirst?.();
        } else stream();
        if (job === jobs[0] && error) shownFirst = false;   // the default failed: show the next row to arrive
      };
      // The first row alone, then the others: its plots are drawn before the long rows take the cores.
      const finished = await (firstOnEngine ? pool.one({ call: (...a) => engine.call(...a) }, jobs[0], task, onRow) : pool.map(jobs.slice(0, 1), task, onRow))
        && await pool.map(jobs.slice(1), task, onRow);
      clearTimeout(frame); frame = 0;
      flush();   // the last rows' log lines and the final count, before the summary line
      running = false;
      app.emit('compare', { done, total, running });
      const seconds = ((performance.now() - t0) / 1000).toFixed(2);
      progress.update({ fraction: done / total, stage: finished ? 'done' : `cancelled after ${done} of ${total} rows` });
      // The summary line comes after the last redraw of the results (below): the table redraws at
      // most every 250 ms while rows arrive, so at this point it may not show the last rows yet.
      const summary = h('li', {}, finished ? `${results.length} of ${total} fits in ${seconds} s.`
        : `Cancelled after ${done} of ${total} rows (${seconds} s); the ${results.length} fitted rows are kept.`);
      if (results.length) {
        clearTimeout(frame); frame = 0;
        await app.save('results', results);
        // The best by leave-one-out is shown, unless another row was picked while the rows arrived.
        const shown = app.session.selected === autoKey ? bestByLoo(results) : results.find((r) => r.key === app.session.selected) ?? bestByLoo(results);
        await app.save('selected', shown.key);
        await app.save('recipe', shown.recipe);   // how the selected profile was made
        app.mark('fit', 'done');
        app.emit('results', results);
      } else if (finished) {
        showError(runBtn, Object.assign(new Error('no fit succeeded; see the list below'), { code: 'FIT_FAILED' }), 'Fit');
      }
      log.append(summary);
      return results.length || finished ? results : null;
    } catch (e) {
      showError(runBtn, e, 'Fit');
      return null;
    } finally {
      if (pendingLog.length) { clearTimeout(frame); frame = 0; flush(); }
      if (running) app.emit('compare', { done, total, running: false });
      running = false; runBtn.disabled = false; cancelBtn.disabled = true;
      progress.done();
    }
  }
  runBtn.addEventListener('click', () => { run({ onFirst: () => app.goto('results') }); });

  /// The recipe of one fit: every setting of steps 1–3 that decides the profile.
  function recipeFor(model, objective, ref, data) {
    const s = app.session, rs = ref.settings;
    const flat = !!s['files.flat'], radial = s.flatMode === 'radial';
    const sample = app.derived.sample;
    return {
      reference: rs.referenceFile ? { chart: 'file', data_digest: ref.data_digest, illuminant: rs.illuminant, observer: rs.observer }
        : { chart: rs.chart, illuminant: rs.illuminant, observer: rs.observer },
      // dark_mode: the mode the worker subtracts the dark frame with (images/handlers.js, setDark)
      capture: { dark_frames: s['files.dark'] ? s['files.dark'].list?.length ?? 1 : 0, dark_mode: 'per_pixel', flat_field: flat && !radial, falloff: flat && radial,
        saturation: storedFullScale(app.derived.image?.metadata),
        // the light trap of step 2 (Abed 2013 App. C step 1) and the flare it subtracted
        ...(sample.lightTrap ? { light_trap: sample.lightTrapCorners, flare: Array.from(sample.lightTrap.mean) } : {}) },
      sampling: { layout: s.layout ?? { chart: 'passport' }, corners: sample.corners, area: s.sampleOptions?.area ?? 0.5,
        exclude: [], exclude_flagged: false, exclude_flags: choice.excludeFlags },
      // the linearisation step's choice (step 2b): the fit trains on the linearised camera RGB
      linearisation: s.linearisation ?? { method: 'identity' },
      // the surface step's correction of a built-in chart's spectra (an uploaded reference stays as read)
      surface: rs.referenceFile ? { method: 'none' } : (s.surface ?? { method: 'none' }),
      // a joint surface fit (Phase II) is anchored to the chart's white patch, so it sets one
      characterisation: { model, objective: choice.objectiveChoices[objective],
        // … and so does Abed's corrected 3×3: μ (eq 27) scales the matrix to the white reference
        white_patch: choice.preserveWhite || jointSurface(s.surface, rs) || model === 'corrected-3x3' ? brightestPatch(data) : '', lab_white: ref.white },
      evaluation: { leave_one_out: true },
    };
  }

  /// First visit: compare everything; `onFirst` runs when the first row is shown. The engine's
  /// worker has just sampled the example and is idle: it fits the first row.
  async function runDefault({ onFirst } = {}) {
    if (!app.derived.sample || !app.derived.reference) return null;
    return run({ onFirst, firstOnEngine: true });
  }
  describeData();
  return { run, runDefault, cancel: () => cancelBtn.click(), runBtn, pool };
}

/// True when the surface stage is fitted in the fit step (Phase II, a built-in chart only).
const jointSurface = (surface, rs) => !rs.referenceFile && surface?.settings?.fit === 'joint';
/// "scaler-offset: mu=0.9641, rho=0.03673" (the numbers to 4 significant digits).
const choiceText = (c) => `${c.method}: ${Object.entries(c.parameters ?? {}).map(([k, v]) => `${k}=${Number(v).toPrecision(4)}`).join(', ')}`;

/// What the linearisation stage (step 2b) does to the camera RGB, for the data note.
function linearisationText(lin, meta) {
  const method = lin?.method ?? 'identity';
  if (meta?.encoding === 'stored' && method === 'identity')
    return `; the chart image is a ${meta.format.toUpperCase()} (not linear) and the linearisation is “identity”: choose one in step 2b`;
  return method === 'identity' ? '' : `; camera RGB linearised by ${method} (step 2b)`;
}

/// The full scale of a TIFF/PNG/JPEG's stored values (255, 65535): the linearisation's x = 1.
/// 0 for a RAW (its linear DN need none).
export const storedFullScale = (m) => (m?.encoding === 'stored' ? m.white_level : 0);

/// "Make Model" of RAW metadata ('' when unknown).
export const cameraOf = (m) => [m?.make, m?.model].filter(Boolean).join(' ');

/// What a fit was trained against (to tell when the current reference differs).
export const referenceText = (ref) => `${ref.source}, illuminant ${ref.settings.illuminant}, CIE ${ref.settings.observer} observer`;

/// The result with the lowest leave-one-out mean CIEDE2000 (training mean when LOO is missing).
function bestByLoo(results) {
  const score = (r) => { const v = metric(r, 'loo', 'mean'); return Number.isFinite(v) ? v : 1e9 + (metric(r, 'training', 'mean') || 0); };
  return results.reduce((a, b) => (score(b) < score(a) ? b : a));
}

/// The patch with the highest reference Y (the chart's white), for white preservation.
function brightestPatch(d) {
  let best = 0;
  for (let i = 1; i < d.ids.length; i++) if (d.xyz[3 * i + 1] > d.xyz[3 * best + 1]) best = i;
  return d.ids[best];
}

function toggle(list, v, on) {
  const i = list.indexOf(v);
  if (on && i < 0) list.push(v);
  if (!on && i >= 0) list.splice(i, 1);
}

/// A fresh session compares everything: every model (duplicates of another's span left out, as
/// in `tristim compare`) with every objective.
function defaultChoice(models, objectives) {
  return { models: models.filter((m) => !m.duplicate_of).map((m) => m.id), objectives: objectives.map((o) => o.id),
    preserveWhite: false };   // excludeFlags: the engine's defaults (excludeFlags, lib/pairs.js)
}

/// The models whose rows a fresh session shows first (the first of these the engine has) while
/// the compare runs: a choice of the page, not a property of the models.
const DEFAULT_MODELS = ['matrix-3x3', 'Finlayson2015-2', 'Shen2008'];

/// The rows (model × objective) in the order they are handed to the workers: first the first
/// default model with the first objective (the first screen shows it while the others run), then
/// the most expensive first — terms × objective weight (least squares has a closed-form
/// leave-one-out; the iterative objectives refit once per fold) — so the last rows are short ones
/// and the workers finish together.
export function rowOrder(modelIds, objectiveIds, nTerms) {
  const weight = { ls: 1, psm: 4, de2000: 10 };
  const cost = (j) => (nTerms.get(j.mId) ?? 10) * (weight[j.obj] ?? 10);
  const jobs = modelIds.flatMap((mId) => objectiveIds.map((obj) => ({ mId, obj })));
  const first = DEFAULT_MODELS.map((id) => jobs.find((j) => j.mId === id && j.obj === objectiveIds[0])).find(Boolean);
  return [...(first ? [first] : []), ...jobs.filter((j) => j !== first).sort((a, b) => cost(b) - cost(a))];
}

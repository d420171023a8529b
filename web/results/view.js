// Step 4: the comparison table of every fitted model (sortable) and, for the selected one, the
// xy diagram with arrows, CIELAB planes, ΔE00 bars, XYZ scatter and swatch pairs; the selected
// fit's uncertainty (the engine's bootstrap, run in the worker in chunks so Cancel stops it):
// intervals next to the means and coefficients, ellipses on the xy and a*b* plots.
import { h, fmt, showError, clearError, progressBar } from '../lib/ui.js';
import { optionsForm, completeChoice } from '../lib/options_form.js';
import { metric, COLUMNS } from '../lib/metrics.js';
import { perPatch, patchTitle } from '../lib/perpatch.js';
import { figure } from '../plots/common.js';
import { xyPlot } from '../plots/xy.js';
import { labPlanePlot, abPlanePlot } from '../plots/lab.js';
import { deBarsPlot } from '../plots/de_bars.js';
import { xyzScatterPlot } from '../plots/xyz_scatter.js';
import { swatchPairsPlot } from '../plots/swatch_pairs.js';
import { referenceText } from '../fit/view.js';
import { chartFiguresTable } from '../fit/charts_table.js';

export function mount(section, app) {
  const tableBox = h('div', { class: 'table-box' });
  const detail = h('div', { class: 'result-detail' });
  const empty = h('p', { class: 'summary' }, 'No fitted model yet: pick models in step 3 and fit them.');
  // While step 3 compares, rows stream in: how many are done, and a Cancel (step 3's).
  const compareText = h('span', {});
  const compareCancel = h('button', { type: 'button', onclick: () => app.views.fit.cancel() }, 'Cancel');
  const compareNote = h('p', { class: 'summary compare-progress', role: 'status', hidden: true }, compareText, ' ', compareCancel);
  app.on('compare', ({ done, total, running }) => {
    compareNote.hidden = !running;
    compareText.textContent = `Comparing every model × objective: ${done} of ${total} rows done; the table fills as they finish.`;
  });
  const uncertainty = bootstrapPanel(app, () => app.session.results?.find((r) => r.key === app.session.selected) ?? app.session.results?.[0],
    () => refresh({ redraw: true }));
  const checks = checksPanel(app, () => refresh());
  section.append(empty, compareNote, tableBox, checks.el, uncertainty.el, detail);
  let sort = { key: 'loo-mean', dir: 1 };
  let shown = null;   // the result whose plots are drawn (redrawn only when it or the reference changes)

  function refresh({ redraw = false } = {}) {
    const results = app.session.results ?? [];
    empty.hidden = results.length > 0;
    uncertainty.el.hidden = checks.el.hidden = !results.length;
    if (!results.length) { tableBox.replaceChildren(); detail.replaceChildren(); shown = null; return; }
    const selected = results.find((r) => r.key === app.session.selected) ?? results[0];
    tableBox.replaceChildren(comparisonTable(results, selected), ...ridgeTable(app.session.ridge ?? [], app.catalog.models));
    if (redraw || selected !== shown) renderDetail(selected);
    shown = selected;
    app.mark('results', 'done');
  }

  // The fit's status word, and its message (why a fit is flagged: ill-conditioned, no leave-one-out
  // figure, …) in smaller type under it, wrapped within the column instead of widening the table.
  function statusCell(fit, stopping) {
    const unstable = stopping?.flagged;
    return h('td', { class: `status${fit.status === 'ok' && !unstable ? '' : ' flagged'}` },
      String(fit.status).replaceAll('_', ' '), fit.message ? h('small', {}, fit.message) : null,
      unstable ? h('small', { class: 'loo-unstable', title: 'the leave-one-out mean moves when the optimiser stops 100× later (tristim compare\'s check): read the least-squares or ridge row of the same model instead' },
        `LOO-unstable: ${fmt(stopping.perturbed_loo_mean)} with 100× tighter stopping`) : null,
      stopping?.checked && !unstable ? h('small', { class: 'loo-stable' }, 'LOO stable under tighter stopping') : null);
  }

  function comparisonTable(results, selected) {
    const col = COLUMNS.find((c) => c.key === sort.key);
    const val = (r) => (col ? metric(r, col.set, col.stat) : 0);
    const loo = (r) => metric(r, 'loo', 'mean');
    const best = results.reduce((a, b) => (Number.isFinite(loo(b)) && !(loo(a) <= loo(b)) ? b : a), results[0]);
    const rows = [...results].sort((a, b) => {
      const va = val(a), vb = val(b);
      if (!Number.isFinite(va)) return 1;
      if (!Number.isFinite(vb)) return -1;
      return sort.dir * (va - vb);
    });
    const th = (c) => {
      const b = h('button', { type: 'button', class: 'sort', onclick: () => { sort = { key: c.key, dir: sort.key === c.key ? -sort.dir : 1 }; refresh(); } }, c.label);
      return h('th', { scope: 'col', 'aria-sort': sort.key === c.key ? (sort.dir > 0 ? 'ascending' : 'descending') : 'none', dataset: { col: c.key } }, b);
    };
    return h('table', { class: 'compare' },
      h('caption', {}, 'CIEDE2000 errors of every fitted model (lower is better). Leave-one-out: each patch predicted by a fit made without it — the honest estimate for colours the model was not trained on (for a model with many terms fitted to CIEDE2000 it also depends on where the optimiser stopped, the loss being flat where the coefficients are not: read it next to the same model\'s least-squares row). Held-out chart: a second chart the fit never saw (– when none was given). Click a heading to sort.'),
      h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, 'Model · objective'), COLUMNS.map(th), h('th', { scope: 'col', class: 'status' }, 'status'), h('th', { scope: 'col' }, 'show'))),
      h('tbody', {}, rows.map((r) => h('tr', { class: [r === selected ? 'selected' : '', r === best && Number.isFinite(loo(r)) ? 'best' : ''].join(' ').trim(), dataset: { key: r.key } },
        h('th', { scope: 'row' }, r.label, r === best && Number.isFinite(loo(r)) ? h('small', { class: 'best-mark', title: 'the lowest leave-one-out mean CIEDE2000' }, ' best') : null),
        COLUMNS.map((c) => h('td', { dataset: { col: c.key } }, fmt(metric(r, c.set, c.stat)), ciText(intervalOf(r, c)))),
        statusCell(r.fit.evaluation.fit, r.stopping),
        h('td', {}, h('button', { type: 'button', 'aria-pressed': String(r === selected), 'aria-label': `Show the plots of ${r.label}`, onclick: () => { app.save('selected', r.key); refresh(); } }, r === selected ? 'shown' : 'show'))))));
  }

  function renderDetail(result) {
    const ref = app.derived.reference;
    const pp = perPatch(result, ref);
    const parts = [];
    if (app.session.example) {
      parts.push(h('p', { class: 'example-note' }, 'This is the built-in example: an X-Rite ColorChecker Passport photographed as a DNG '
        + '(Canon EOS 550D with Magic Lantern, from the tinydng project, MIT licence), sampled and fitted in this page. '
        + 'Load your own RAW in step 2, or change the reference in step 1.'));
    }
    parts.push(h('h3', {}, `Selected: ${result.label}`));
    if (result.referenceText) {
      parts.push(h('p', { class: 'summary' }, `Trained against the ${result.referenceText}.`));
      if (ref && referenceText(ref) !== result.referenceText) {
        parts.push(h('p', { class: 'unavailable', role: 'status' }, `The reference in step 1 has changed since this fit (now: ${referenceText(ref)}). Fit again in step 3 to use it.`));
      }
    }
    const rows = pp.rows;
    const arrows = rows.filter((r) => Number.isFinite(r.xe)).map((r) => ({ id: r.id, x1: r.x, y1: r.y, x2: r.xe, y2: r.ye, title: patchTitle(r) }));
    const points = rows.map((r) => ({ id: r.id, x: r.x, y: r.y, fill: r.fill, title: patchTitle(r) }));
    const obs = ref?.settings?.observer ?? '1931';
    const [Xw, Yw, Zw] = ref?.white ?? [0, 0, 0];
    const white = Xw + Yw + Zw > 0 ? { x: Xw / (Xw + Yw + Zw), y: Yw / (Xw + Yw + Zw) } : null;
    const figs = [
      figure(xyPlot({ locus: app.derived.locus, points, arrows, white, observer: obs, width: 410, zoom: true }),
        { name: 'xy-arrows', caption: `CIE ${obs} xy, zoomed to the patches: reference (dot) → estimate (arrow head); dashed: sRGB gamut` }),
    ];
    const boot = result.bootstrap;
    if (boot) {
      const el = ellipseCaption(boot);
      figs[0] = figure(xyPlot({ locus: app.derived.locus, points, arrows, white, observer: obs, width: 410, zoom: true,
        ellipses: rows.map((r, i) => ({ id: r.id, cx: r.xe, cy: r.ye, cov: boot.predicted_xy_covariance[i], k: boot.ellipse_scale })) }),
      { name: 'xy-arrows', caption: `CIE ${obs} xy, zoomed to the patches: reference (dot) → estimate (arrow head); dashed: sRGB gamut; ${el}` });
      figs.push(figure(abPlanePlot(rows, rows.map((r, i) => ({ id: r.id, cx: r.ae, cy: r.be, cov: boot.predicted_ab_covariance[i], k: boot.ellipse_scale }))),
        { name: 'lab-a-b', caption: `CIELAB a*–b*: reference (dot) → estimate (small dot); ${el}` }));
    }
    figs.push(figure(labPlanePlot(rows, 'a'), { name: 'lab-a-L', caption: 'CIELAB a*–L*: reference (dot) → estimate (small dot)' }));
    figs.push(figure(labPlanePlot(rows, 'C'), { name: 'lab-C-L', caption: 'CIELAB C*–L*: reference (dot) → estimate (small dot)' }));
    figs.push(figure(deBarsPlot(rows), { name: 'de2000-bars', caption: 'CIEDE2000 per patch, split into ΔL/ΔC/ΔH shares; the chip under each bar is the patch', className: 'wide' }));
    figs.push(figure(xyzScatterPlot(rows), { name: 'xyz-scatter', caption: 'Estimated vs reference X, Y, Z; dashed: identity', className: 'wide' }));
    figs.push(figure(swatchPairsPlot(rows), { name: 'swatch-pairs', caption: 'Reference (square) and estimate (disc), display sRGB' }));
    const mean = rows.reduce((s, r) => s + (Number.isFinite(r.dE) ? r.dE : 0), 0) / rows.length;
    parts.push(h('p', { class: 'summary' }, `${rows.length} training patches; mean ΔE00 ${fmt(mean)}; `
      + `condition number ${fmt(result.fit.evaluation.fit.condition_number, 1)}`
      + (result.fit.evaluation.fit.mu ? `; corrected 3×3 white scaling μ = ${fmt(result.fit.evaluation.fit.mu, 4)} (Abed 2013 eq 27)` : '') + '.'));
    if (result.fit.charts?.length) parts.push(chartFiguresTable(result.fit.charts));   // several chart images (issue 48)
    if (boot) parts.push(bootstrapSummary(result, app.catalog.models));
    parts.push(h('div', { class: 'plots' }, figs));
    // The same numbers as a table, for keyboard and screen-reader users (and copying).
    const f2 = (v) => fmt(v, 2);
    parts.push(h('details', { class: 'per-patch' }, h('summary', {}, 'Per-patch numbers of the selected model'),
      h('table', { class: 'patch-table' },
        h('caption', {}, 'Reference and estimated XYZ (white Y = 100), CIELAB, and CIEDE2000 with its ΔL, ΔC, ΔH terms'),
        h('thead', {}, h('tr', {}, ['Patch', 'X', 'Y', 'Z', 'X est', 'Y est', 'Z est', 'L*', 'a*', 'b*', 'L* est', 'a* est', 'b* est', 'ΔE00', 'ΔL', 'ΔC', 'ΔH'].map((t) => h('th', { scope: 'col' }, t)))),
        h('tbody', {}, rows.map((r) => h('tr', { dataset: { id: r.id } }, h('th', { scope: 'row' }, r.id),
          [r.X, r.Y, r.Z, r.Xe, r.Ye, r.Ze, r.L, r.a, r.b, r.Le, r.ae, r.be, r.dE, r.dL, r.dC, r.dH].map((v) => h('td', {}, f2(v)))))))));
    detail.replaceChildren(...parts);
  }

  app.on('results', () => refresh());
  app.on('reference', () => { if (app.session.results?.length) refresh({ redraw: true }); });
  /// A line shown while there is nothing to show yet (e.g. the example being fitted).
  const setStatus = (text) => { empty.textContent = text; };
  return { refresh, setStatus };
}

/// The bootstrap's interval of a comparison-table cell (the training and leave-one-out means), or null.
function intervalOf(result, column) {
  if (!result.bootstrap || column.stat !== 'mean') return null;
  return column.set === 'training' ? result.bootstrap.train_ci : column.set === 'loo' ? result.bootstrap.loo_ci ?? null : null;
}
/// " [lo, hi]" under a number, titled with its level.
const ciText = (ci) => (ci ? h('small', { class: 'ci', title: `${fmtLevel(ci.level)} bootstrap interval` }, ` [${fmt(ci.lo)}, ${fmt(ci.hi)}]`) : null);
const fmtLevel = (level) => `${+(100 * level).toFixed(2)} %`;

/// What the ellipses are, for the plots' captions (the legend line).
function ellipseCaption(b) {
  return `ellipses: each patch's predicted ${fmtLevel(b.level)} region over ${b.resamples} bootstrap refits`
    + ` (covariance of the refits' predictions widened by ${(b.inflation * b.inflation).toFixed(4)} as the coefficients' (HC1),`
    + ` ×k = ${b.ellipse_scale.toFixed(3)}, the ${fmtLevel(b.level)} radius for a covariance estimated from the patches), drawn to scale`;
}

/// The selected fit's bootstrap: how it ran, its means' intervals and a table of every coefficient
/// with its interval (the profile's matrix; its covariance is in the exported profile JSON).
function bootstrapSummary(result, models) {
  const b = result.bootstrap;
  const names = models.find((m) => m.id === result.modelId)?.term_names ?? [];
  const loo = b.loo_ci ? `; leave-one-out mean ΔE00 ${fmt(metric(result, 'loo', 'mean'))} [${fmt(b.loo_ci.lo)}, ${fmt(b.loo_ci.hi)}]` : '';
  const g = (v) => (Math.abs(v) >= 1e-3 || v === 0 ? v.toFixed(5) : v.toExponential(3));
  return h('div', { class: 'bootstrap-summary' },
    h('p', { class: 'summary' }, `Uncertainty: ${b.resamples} bootstrap resamples over the ${b.resampling === 'patches+pixels'
      ? "patches and each patch's pixels (the sampled image's σ and pixel count)" : 'patches only'} (seed ${b.seed}`
      + `${b.failed ? `, ${b.failed} refits refused` : ''}), ${fmtLevel(b.level)} intervals: training mean ΔE00 ${fmt(metric(result, 'training', 'mean'))}`
      + ` [${fmt(b.train_ci.lo)}, ${fmt(b.train_ci.hi)}]${loo}. The coefficients' intervals are widened by ${b.inflation.toFixed(4)} (HC1, for the patches the fit spends on them).`),
    h('table', { class: 'coefficients' },
      h('caption', {}, `Coefficients of the selected model with their ${fmtLevel(b.level)} bootstrap intervals (rows: X, Y, Z; columns: the model's terms)`),
      h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, ''), b.coefficients[0].map((_, t) => h('th', { scope: 'col' }, names[t] ?? `term ${t + 1}`)))),
      h('tbody', {}, b.coefficients.map((row, c) => h('tr', {}, h('th', { scope: 'row' }, 'XYZ'[c]),
        row.map((k) => h('td', { dataset: { lo: k.ci.lo, hi: k.ci.hi } }, g(k.value), h('small', { class: 'ci' }, ` [${g(k.ci.lo)}, ${g(k.ci.hi)}]`))))))));
}

/// Number of resamples per call to the worker: between two calls the worker takes the Cancel.
const CHUNK = 50;

/// The sampled image's pixel statistics of a result's training patches, {std: 3N, n: N} in the
/// order of `ids` (the engine resamples each patch's pixels from them, as `tristim fit --rgb` does
/// with `tristim sample`'s σ and n columns), or null — patches only — when a patch has none (a
/// patch table without σ, a second chart image).
function pixelStats(app, ids) {
  const s = app.derived.sample;
  if (!s?.std || !s?.n || app.derived.sample2) return null;
  const at = new Map(s.ids.map((id, i) => [id, i]));
  if (!ids.every((id) => at.has(id))) return null;
  return { std: Float64Array.from(ids.flatMap((id) => [0, 1, 2].map((k) => s.std[3 * at.get(id) + k]))),
    n: Float64Array.from(ids.map((id) => s.n[at.get(id)])) };
}

/// "Uncertainty (bootstrap)": the settings form (the engine's bootstrapOptions table), Run, Cancel
/// and progress; the result is kept on the selected result (its `bootstrap`, and its profile JSON
/// gains the intervals and covariance, as `tristim fit --bootstrap` writes it).
function bootstrapPanel(app, selected, onDone) {
  const { engine } = app;
  const info = app.catalog.bootstrapOptions;
  const choice = completeChoice(info, app.session.bootstrapChoice);
  const runBtn = h('button', { type: 'button', class: 'primary', dataset: { action: 'bootstrap' } }, 'Run the bootstrap');
  const cancelBtn = h('button', { type: 'button', class: 'cancel', disabled: true, dataset: { action: 'bootstrap-cancel' } }, 'Cancel');
  runBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'bootstrap-error' });
  runBtn.setAttribute('aria-describedby', 'bootstrap-error');
  const progress = progressBar('Bootstrap');
  const note = h('p', { class: 'summary bootstrap-note', role: 'status' });
  const el = h('fieldset', { class: 'uncertainty', hidden: true },
    h('legend', {}, info.label),
    h('p', { class: 'hint' }, `How sure the selected fit's figures are: the fit is repeated on charts resampled from its own patches `
      + `(and, for a sampled photograph with a linear stage, from each patch's pixels: its mean redrawn from σ/√n); `
      + `intervals appear next to the means and coefficients, ellipses on the xy and a*b* plots. ${info.reference}.`),
    h('div', { class: 'controls' }, optionsForm(info, choice, () => app.save('bootstrapChoice', JSON.parse(JSON.stringify(choice))))),
    h('div', { class: 'controls' }, runBtn, cancelBtn, runBtn._errorSlot), progress.el, note);
  let cancel = false;
  cancelBtn.addEventListener('click', () => { cancel = true; cancelBtn.disabled = true; });
  runBtn.addEventListener('click', async () => {
    const r = selected();
    if (!r) return;
    clearError(runBtn);
    cancel = false; runBtn.disabled = true; cancelBtn.disabled = false;
    progress.start('Bootstrap…');
    note.textContent = '';
    const t0 = performance.now();
    let done = 0, total = 0;
    try {
      const ev = r.fit.evaluation;
      ({ done, total } = await engine.call('bootstrapStart', { recipe: r.fit.recipe, ids: r.ids, rgb: r.rgb, xyz: r.xyz, pixels: pixelStats(app, r.ids),
        loo: ev.has_loo ? ev.loo.patches.dE00 : null, settings: choice }));
      while (done < total && !cancel) {
        ({ done, total } = await engine.call('bootstrapStep', { count: CHUNK }));
        progress.update({ fraction: done / total, stage: `${done} of ${total} resamples (${r.label})` });
      }
      if (cancel) {
        await engine.call('bootstrapCancel');
        note.textContent = `Cancelled after ${done} of ${total} resamples; nothing kept.`;
        return;
      }
      const { bootstrap, profile } = await engine.call('bootstrapResult', { profile: r.fit.profile });
      r.bootstrap = bootstrap;
      r.fit.profile = profile;
      note.textContent = `${r.label}: ${bootstrap.resamples} resamples in ${(performance.now() - t0).toFixed(0)} ms.`;
      await app.save('results', app.session.results);
      onDone();
    } catch (e) {
      showError(runBtn, e, 'Bootstrap');
    } finally {
      runBtn.disabled = false; cancelBtn.disabled = true;
      progress.done();
    }
  });
  return { el };
}

/// The ridge rows (`tristim compare --ridge`'s "ridge" rows, the same object): each model by ridge
/// least squares, λ by leave-one-out. A session saved before the rows had that form ({row, lambda})
/// shows none until the checks run again.
function ridgeTable(saved, models) {
  const rows = saved.filter((r) => typeof r.model === 'string');
  if (!rows.length) return [];
  const label = (id) => models.find((m) => m.id === id)?.label ?? id;
  return [h('table', { class: 'compare ridge' },
    h('caption', {}, 'Ridge least squares (as tristim compare --ridge): each model refitted with a penalty on its coefficients, '
      + 'the penalty λ (relative to the largest squared singular value of the design) chosen by leave-one-out, so a many-term model no longer '
      + 'depends on where an optimiser stops. λ = 0 is plain least squares: the ridge row is never worse held out than it.'),
    h('thead', {}, h('tr', {}, ['Model (ridge)', 'training mean', 'leave-one-out mean', 'leave-one-out max', 'λ', 'status'].map((t) => h('th', { scope: 'col' }, t)))),
    h('tbody', {}, rows.map((row) => h('tr', { dataset: { model: row.model } }, h('th', { scope: 'row' }, label(row.model)),
      ...(row.ok ? [fmt(row.train_dE00.mean), fmt(row.loo_dE00.mean), fmt(row.loo_dE00.max), row.lambda.toExponential(2)].map((v) => h('td', {}, v))
        : [h('td', { colspan: 4 }, `${row.message} (${row.error_code})`)]),
      h('td', {}, row.ok ? row.message || 'ok' : 'refused')))))];
}

/// "Check the leave-one-out figures": for every fitted row, whether its leave-one-out mean depends
/// on where the optimiser stops, and every fitted model by ridge least squares (the engine's
/// checks, run in the worker one row at a time).
function checksPanel(app, onDone) {
  const { engine } = app;
  const runBtn = h('button', { type: 'button', dataset: { action: 'loo-checks' } }, 'Check the leave-one-out figures (stopping point, ridge)');
  runBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'loo-checks-error' });
  runBtn.setAttribute('aria-describedby', 'loo-checks-error');
  const progress = progressBar('Checks');
  const el = h('div', { class: 'loo-checks', hidden: true },
    h('p', { class: 'hint' }, 'A many-term model fitted by an optimiser can give a leave-one-out figure that depends on where the optimiser stopped '
      + '(the loss is flat where the coefficients are not determined). The check refits each fold with 100× tighter stopping and flags a row whose '
      + 'mean moves by more than 0.05 or 2 %; ridge least squares gives every model a stable, closed-form alternative.'),
    h('div', { class: 'controls' }, runBtn, runBtn._errorSlot), progress.el);
  runBtn.addEventListener('click', async () => {
    const results = app.session.results ?? [];
    clearError(runBtn);
    runBtn.disabled = true;
    progress.start('Checking…');
    try {
      const data = (r) => ({ recipe: r.fit.recipe, ids: r.ids, rgb: r.rgb, xyz: r.xyz });
      const firstOf = new Map();
      for (const r of results) if (!firstOf.has(r.modelId) && r.modelId !== 'corrected-3x3') firstOf.set(r.modelId, r);
      const total = results.length + firstOf.size;
      let done = 0;
      for (const r of results) {
        const ev = r.fit.evaluation;
        if (ev.has_loo) r.stopping = await engine.call('looStability', { ...data(r), loo_mean: ev.loo.dE00.mean, condition_number: ev.fit.condition_number });
        progress.update({ fraction: ++done / total, stage: `${done} of ${total}: ${r.label}` });
      }
      const ridge = [];
      for (const r of firstOf.values()) {
        ridge.push(await engine.call('ridgeRow', data(r)));
        progress.update({ fraction: ++done / total, stage: `${done} of ${total}: ridge ${r.modelId}` });
      }
      await app.save('ridge', ridge);
      await app.save('results', results);
      onDone();
    } catch (e) {
      showError(runBtn, e, 'Checks');
    } finally {
      runBtn.disabled = false;
      progress.done();
    }
  });
  return { el };
}

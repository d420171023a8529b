// Step 4: the comparison table of every fitted model (sortable) and, for the selected one, the
// xy diagram with arrows, CIELAB planes, ΔE00 bars, XYZ scatter and swatch pairs.
import { h, fmt } from '../lib/ui.js';
import { metric, COLUMNS } from '../lib/metrics.js';
import { perPatch, patchTitle } from '../lib/perpatch.js';
import { figure } from '../plots/common.js';
import { xyPlot } from '../plots/xy.js';
import { labPlanePlot } from '../plots/lab.js';
import { deBarsPlot } from '../plots/de_bars.js';
import { xyzScatterPlot } from '../plots/xyz_scatter.js';
import { swatchPairsPlot } from '../plots/swatch_pairs.js';
import { referenceText } from '../fit/view.js';

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
  section.append(empty, compareNote, tableBox, detail);
  let sort = { key: 'loo-mean', dir: 1 };
  let shown = null;   // the result whose plots are drawn (redrawn only when it or the reference changes)

  function refresh({ redraw = false } = {}) {
    const results = app.session.results ?? [];
    empty.hidden = results.length > 0;
    if (!results.length) { tableBox.replaceChildren(); detail.replaceChildren(); shown = null; return; }
    const selected = results.find((r) => r.key === app.session.selected) ?? results[0];
    tableBox.replaceChildren(comparisonTable(results, selected));
    if (redraw || selected !== shown) renderDetail(selected);
    shown = selected;
    app.mark('results', 'done');
  }

  // The fit's status word, and its message (why a fit is flagged: ill-conditioned, no leave-one-out
  // figure, …) in smaller type under it, wrapped within the column instead of widening the table.
  function statusCell(fit) {
    return h('td', { class: `status${fit.status === 'ok' ? '' : ' flagged'}` },
      String(fit.status).replaceAll('_', ' '), fit.message ? h('small', {}, fit.message) : null);
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
        COLUMNS.map((c) => h('td', { dataset: { col: c.key } }, fmt(metric(r, c.set, c.stat)))),
        statusCell(r.fit.evaluation.fit),
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
    figs.push(figure(labPlanePlot(rows, 'a'), { name: 'lab-a-L', caption: 'CIELAB a*–L*: reference (dot) → estimate (small dot)' }));
    figs.push(figure(labPlanePlot(rows, 'C'), { name: 'lab-C-L', caption: 'CIELAB C*–L*: reference (dot) → estimate (small dot)' }));
    figs.push(figure(deBarsPlot(rows), { name: 'de2000-bars', caption: 'CIEDE2000 per patch, split into ΔL/ΔC/ΔH shares; the chip under each bar is the patch', className: 'wide' }));
    figs.push(figure(xyzScatterPlot(rows), { name: 'xyz-scatter', caption: 'Estimated vs reference X, Y, Z; dashed: identity', className: 'wide' }));
    figs.push(figure(swatchPairsPlot(rows), { name: 'swatch-pairs', caption: 'Reference (square) and estimate (disc), display sRGB' }));
    const mean = rows.reduce((s, r) => s + (Number.isFinite(r.dE) ? r.dE : 0), 0) / rows.length;
    parts.push(h('p', { class: 'summary' }, `${rows.length} training patches; mean ΔE00 ${fmt(mean)}; `
      + `condition number ${fmt(result.fit.evaluation.fit.condition_number, 1)}`
      + (result.fit.evaluation.fit.mu ? `; corrected 3×3 white scaling μ = ${fmt(result.fit.evaluation.fit.mu, 4)} (Abed 2013 eq 27)` : '') + '.'));
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

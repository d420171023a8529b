// The per-chart figures of a fit on several chart images (issue 48; the engine's chart_figures,
// FitOutcome.charts): each chart's training and leave-one-out CIEDE2000 over its own rows, and
// held out — the model fitted on the other charts only (Abed 2013 Table IV's train-on-one,
// test-on-another).
import { h, fmt } from '../lib/ui.js';

/// A table of `charts` (the profile's "charts" rows: {chart, patches, training, loo, held_out,
/// held_out_error}, a figure {dE00_mean, dE00_max} or null), or null when the fit had one chart.
export function chartFiguresTable(charts) {
  if (!charts?.length) return null;
  const pair = (s) => (s ? [h('td', {}, fmt(s.dE00_mean)), h('td', {}, fmt(s.dE00_max))] : [h('td', {}, '–'), h('td', {}, '–')]);
  return h('table', { class: 'chart-figures' },
    h('caption', {}, 'Per chart image: mean and max CIEDE2000 of its patches in training, leave-one-out, and held out (the same model and objective fitted on the other charts only).'),
    h('thead', {}, h('tr', {}, ['Chart', 'Patches', 'Training mean', 'max', 'Leave-one-out mean', 'max', 'Held-out mean', 'max'].map((t) => h('th', { scope: 'col' }, t)))),
    h('tbody', {}, charts.map((c, k) => h('tr', { dataset: { chart: String(k + 1) } },
      h('th', { scope: 'row' }, `${k + 1}: ${c.chart}`), h('td', {}, String(c.patches)),
      pair(c.training), pair(c.loo),
      c.held_out ? pair(c.held_out) : h('td', { colspan: 2, class: 'unavailable' }, c.held_out_error || '–')))));
}

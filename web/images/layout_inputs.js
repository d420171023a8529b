// The custom grid's number inputs (rows, columns, gap, four margins) and the sampled area's, built
// from the engine's layout option table (app.catalog.layoutOptions: layout_option_table() rows —
// label, unit, min/max/step/default), for step 2's chart image and each extra chart image.
import { h, field, errorSlot, numberValue } from '../lib/ui.js';

export const labelOf = (o) => (o.unit ? `${o.label} (${o.unit})` : o.label);
/// A layout's name: its built-in chart's, or the custom grid's.
export const layoutName = (app, id) => app.catalog.charts.find((c) => c.id === id)?.name ?? (id === 'custom' ? 'Custom grid (rows × columns)' : id);
const MARGINS = ['margin_left', 'margin_top', 'margin_right', 'margin_bottom'];

/// The number input of layout option `name` (the table's bounds, step and default; `value` over it).
export function optionInput(app, name, value, attrs = {}) {
  const o = app.catalog.layoutOptions.find((x) => x.name === name);
  return h('input', { type: 'number', min: o.min, max: o.max, step: o.step || (o.type === 'integer' ? 1 : 'any'),
    value: value ?? o.default_number, title: o.description, 'data-layout-option': name, ...attrs });
}

/// The custom grid's inputs: {el, boxes, read(chart), set(layout)}. read() is the engine's
/// LayoutOptions for layout `chart`; a box that cannot be read (a typo; rows or columns left empty)
/// throws INVALID_ARGUMENT carrying the box; gap and margins left empty are 0.
export function customGrid(app, layout = {}) {
  const spec = Object.fromEntries(app.catalog.layoutOptions.map((o) => [o.name, o]));
  const rowsIn = optionInput(app, 'rows', layout.rows, { 'data-layout': 'rows' });
  const colsIn = optionInput(app, 'columns', layout.columns, { 'data-layout': 'columns' });
  const gapIn = optionInput(app, 'gap', undefined, { 'data-layout': 'gap' });
  const marginIns = MARGINS.map((name) => optionInput(app, name, undefined, { 'data-layout': name, 'aria-label': labelOf(spec[name]) }));
  const el = h('span', { class: 'custom-grid' }, field(labelOf(spec.rows), rowsIn), field(labelOf(spec.columns), colsIn),
    field(labelOf(spec.gap), gapIn),
    h('fieldset', { class: 'margins' }, h('legend', {}, 'Margins inside the corners (left, top, right, bottom)'), marginIns,
      marginIns.map((i) => errorSlot(i))));
  function read(chart) {
    if (chart !== 'custom') return { chart };
    const margins = marginIns.map((i) => numberValue(i, 0));   // read first: a margin's typo is shown even while rows is empty
    return { chart, rows: numberValue(rowsIn), columns: numberValue(colsIn), margins, gap: numberValue(gapIn, 0) };
  }
  /// Shows a stored layout's values (a session saved before the layout crossed as its JSON,
  /// margin_left …, is read too).
  function set(L) {
    if (L.rows) rowsIn.value = L.rows;
    if (L.columns) colsIn.value = L.columns;
    if (L.gap >= 0) gapIn.value = L.gap;
    const margins = 'margin_left' in L ? MARGINS.map((k) => L[k]) : (L.margins ?? []);
    margins.forEach((m, i) => { if (m) marginIns[i].value = m; });
  }
  return { el, boxes: [rowsIn, colsIn, gapIn, ...marginIns], read, set };
}

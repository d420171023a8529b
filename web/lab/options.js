// The Lab's number boxes from the engine's table (lab_option_table, the catalog's labOptions): each
// box's bounds, step, default and description, and its field's label with the unit, are the row's —
// the bounds the engine's lab functions enforce (a value beyond them is refused, INVALID_ARGUMENT).
import { h, field } from '../lib/ui.js';

/// `box(name, key, value)`: an <input type=number> for row `name` ('render.exposure'…), data-lab
/// `key`, holding `value` (the session's) or the row's default. `field(box)`: the box in a field
/// labelled "label (unit)".
export function labOptionBoxes(app) {
  const rows = new Map((app.catalog.labOptions ?? []).map((o) => [o.name, o]));
  const row = (name) => {
    const o = rows.get(name);
    if (!o) throw new Error(`the engine's lab option table has no '${name}'`);
    return o;
  };
  return {
    box: (name, key, value) => {
      const o = row(name);
      return h('input', { type: 'number', class: 'num', min: o.min, max: o.max, step: o.step || (o.type === 'integer' ? 1 : 'any'),
        value: value ?? o.default_number, title: o.description, 'data-lab': key, 'data-lab-option': name });
    },
    field: (box) => {
      const o = row(box.dataset.labOption);
      return field(o.unit ? `${o.label} (${o.unit})` : o.label, box);
    },
  };
}

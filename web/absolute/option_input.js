// A number box built from one row of an engine option table (OptionSpec: name, label, unit,
// min/max/step, default, description) — the Absolute mode's recipe options (absolute_option_table)
// and the sensitivity estimate's (sensitivity_option_table). `data-<table>-option` names the row
// (tests/web/catalog_pickers.test.mjs checks each box against it).
import { h } from '../lib/ui.js';

/// "label (unit)", or the label alone.
export const optionLabel = (row) => (row.unit ? `${row.label} (${row.unit})` : row.label);

/// <input type=number> bounded as `row`, showing its default; `attrs` add to or override it. A row
/// whose min is exclusive (min_exclusive: the engine refuses min itself, e.g. the zone parameter w)
/// marks the box invalid at min as the browser does past max (the engine's coded error follows).
export function optionInput(table, row, attrs = {}) {
  const input = h('input', { type: 'number', min: row.min, max: row.max, step: row.step || (row.type === 'integer' ? 1 : 'any'),
    value: row.default_number, title: row.description, [`data-${table}-option`]: row.name, ...attrs });
  if (row.min_exclusive && row.min != null) {  // a bound that is not a number crosses as null
    input.dataset.minExclusive = '';
    const check = () => {
      const bad = input.value !== '' && Number(input.value) <= row.min;
      input.setCustomValidity(bad ? `${row.label}: more than ${row.min}` : '');
      if (bad) input.setAttribute('aria-invalid', 'true');   // outlined as the page's other refused inputs
      else input.removeAttribute('aria-invalid');
    };
    input.addEventListener('input', check);
    input.addEventListener('change', check);
  }
  return input;
}

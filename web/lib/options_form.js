// Options forms built from the engine's method tables: one control per OptionSpec row of a
// MethodInfo (number / integer / boolean / choice / text), labelled, bounded and with the row's
// default. A form edits a MethodChoice {method, parameters, settings} as the engine reads it.
import { h, field, select, numberValue, showError, clearError } from './ui.js';

const NUMERIC = new Set(['number', 'integer', 'boolean']);

/// The table's defaults as a MethodChoice (what a fresh session starts from).
export function defaultChoice(info) {
  const c = { method: info.id, parameters: {}, settings: {} };
  for (const o of info.options) {
    if (NUMERIC.has(o.type)) c.parameters[o.name] = o.default_number;
    else c.settings[o.name] = o.default_text;
  }
  return c;
}

/// `choice` with every option of `info` present (a stored choice from an older table keeps what
/// still exists and takes the defaults for the rest).
export function completeChoice(info, choice) {
  const d = defaultChoice(info);
  for (const o of info.options) {
    const from = NUMERIC.has(o.type) ? 'parameters' : 'settings';
    if (choice?.[from]?.[o.name] !== undefined) d[from][o.name] = choice[from][o.name];
  }
  return d;
}

/// Controls for every option of `info`, editing `choice` in place; onChange(choice) after each edit.
export function optionsForm(info, choice, onChange) {
  return info.options.map((o) => {
    const hint = o.description || null;
    if (o.type === 'boolean') {
      const cb = h('input', { type: 'checkbox', checked: !!choice.parameters[o.name], dataset: { option: o.name } });
      cb.id = `${info.id}-${o.name}`;
      cb.addEventListener('change', () => { choice.parameters[o.name] = cb.checked ? 1 : 0; onChange(choice); });
      return h('div', { class: 'check', title: hint }, cb, h('label', { for: cb.id }, o.label));
    }
    if (o.type === 'choice') {
      const s = select(o.choices, choice.settings[o.name]);
      s.dataset.option = o.name;
      s.addEventListener('change', () => { choice.settings[o.name] = s.value; onChange(choice); });
      return field(o.label, s, hint);
    }
    if (o.type === 'text') {
      const t = h('input', { type: 'text', value: choice.settings[o.name], dataset: { option: o.name } });
      t.addEventListener('change', () => { choice.settings[o.name] = t.value; onChange(choice); });
      return field(o.label, t, hint);
    }
    const bounded = o.max > o.min;
    const i = h('input', { type: 'number', value: choice.parameters[o.name], step: o.type === 'integer' ? 1 : 'any',
      min: bounded ? o.min : null, max: bounded ? o.max : null, dataset: { option: o.name } });
    // A typo or an empty box is shown next to the box; the fits keep the last number it held.
    const read = () => {
      let v;
      try { v = numberValue(i); } catch (e) {
        e.message += ` (the fits keep ${choice.parameters[o.name]})`;
        showError(i, e);
        return;
      }
      clearError(i);
      choice.parameters[o.name] = v;
      onChange(choice);
    };
    i.addEventListener('change', read);
    // A typo typed into an empty box, or cleared, gives no change event (its value is '' before and
    // after): the box is read again on leaving it.
    i.addEventListener('blur', () => { if (i.hasAttribute('aria-invalid') || i.validity.badInput) read(); });
    return field(o.label, i, hint);
  });
}

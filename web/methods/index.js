// The method list: one descriptor per model family (id, label, default options, options form).
// The picker shows what the engine's listModels() offers, each with the descriptor that matches
// its id (or a plain one), so a new engine model appears without a page change.
import linear from './linear.js';
import affine from './affine.js';
import polynomial from './polynomial.js';
import rootPolynomial from './root_polynomial.js';

const DESCRIPTORS = [affine, rootPolynomial, polynomial, linear];

/// engine model entry (string or {id, label, ...}) -> descriptor with id, label, defaults, form.
export function describe(model) {
  const id = typeof model === 'string' ? model : String(model.id);
  const engineLabel = typeof model === 'string' ? null : (model.label ?? model.name);
  const d = DESCRIPTORS.find((x) => x.match(id));
  const defaults = { ...(d?.defaults ?? {}), ...(typeof model === 'object' ? model.defaults ?? {} : {}) };
  return {
    id,
    label: engineLabel ?? d?.label ?? id,
    about: d?.about ?? (typeof model === 'object' ? model.description ?? '' : ''),
    defaults,
    form: d?.form ? (opts, onChange) => d.form.call({ id }, opts, onChange) : () => null,
  };
}

/// The models a fresh session fits (the first three the engine offers from this preference list).
export const DEFAULT_MODEL_PATTERNS = [/^(linear|matrix|3x3)/i, /root/i, /(poly|shen)/i];

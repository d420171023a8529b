// The method list: one descriptor per model family (family label, about, default options, an
// optional options form). The picker shows the models the engine's listModels() offers, grouped
// by the descriptor that matches each id, so a new engine model appears without a page change.
import matrix from './matrix.js';
import polynomial from './polynomial.js';
import rootPolynomial from './root_polynomial.js';
import guarnera from './guarnera.js';

export const FAMILIES = [matrix, rootPolynomial, polynomial, guarnera];
const OTHER = { family: 'Other models', about: '', defaults: {}, form: () => null };

/// engine model entry (string or {id, label, reference, duplicateOf, ...}) -> descriptor.
export function describe(model) {
  const m = typeof model === 'string' ? { id: model } : model;
  const id = String(m.id);
  const d = FAMILIES.find((x) => x.match(id)) ?? OTHER;
  const dup = m.duplicateOf ?? m.duplicate_of ?? '';
  return {
    id,
    label: m.label ?? id,
    family: d.family,
    about: m.reference ?? d.about,
    duplicateOf: dup,
    defaults: { ...d.defaults, ...(m.defaults ?? {}) },
    form: (opts, onChange) => d.form(opts, onChange),
  };
}

/// The models a fresh session fits: these ids when the engine has them, else the first three.
export const DEFAULT_MODELS = ['matrix-3x3', 'Finlayson2015-2', 'Shen2008'];

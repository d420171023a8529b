// The model families: one descriptor per family (family label, about). The picker shows the
// models the engine's listModels() offers, grouped by the descriptor that matches each id, so a
// new engine model appears without a page change. A family's `about` is advice only: each
// model's citation is its engine row's `reference` (the picker's title), never written here.
import matrix from './matrix.js';
import polynomial from './polynomial.js';
import rootPolynomial from './root_polynomial.js';
import guarnera from './guarnera.js';

export const FAMILIES = [matrix, rootPolynomial, polynomial, guarnera];
const OTHER = { family: 'Other models', about: '' };

/// An engine ModelInfo row (or an id) with its family: {id, label, family, about, duplicate_of}.
export function describe(model) {
  const m = typeof model === 'string' ? { id: model } : model;
  const d = FAMILIES.find((x) => x.match(m.id)) ?? OTHER;
  return { id: m.id, label: m.label ?? m.id, family: d.family, about: m.reference ?? d.about, duplicate_of: m.duplicate_of ?? '' };
}

/// The model a fresh session shows first (the first of these the engine has) while the compare runs.
export const DEFAULT_MODELS = ['matrix-3x3', 'Finlayson2015-2', 'Shen2008'];

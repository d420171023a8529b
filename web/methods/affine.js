// Affine 3x4 matrix with offset (Abed et al. 2013 eq 7).
export default {
  match: (id) => /(affine|3x4|offset)/i.test(id),
  label: 'Affine 3×4 matrix (with offset)',
  about: 'Abed et al. 2013 eq (7); 12 coefficients.',
  defaults: {},
  form: () => null,
};

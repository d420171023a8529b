// Linear 3x3 matrix (Abed et al. 2013 eq 6): XYZ = M · RGB.
export default {
  match: (id) => /^(linear|matrix|3x3|m3x3|matrix3x3)/i.test(id),
  label: 'Linear 3×3 matrix',
  about: 'Abed et al. 2013 eq (6); 9 coefficients.',
  defaults: {},
  form: () => null,
};

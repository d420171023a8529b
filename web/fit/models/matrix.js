// Linear 3×3 and affine 3×4 matrices (Abed et al. 2013 eqs 6, 7, 26).
export default {
  family: 'Matrices',
  match: (id) => /^matrix-/i.test(id),
  about: 'XYZ = M·RGB, or M·[R, G, B, 1] with an offset.',
};

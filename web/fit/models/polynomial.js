// Polynomial expansions: Shen et al. 2008's 10-term vector (eq 23) and the Cheung et al. 2004
// family (3–35 terms, colour-science's term order).
export default {
  family: 'Polynomials',
  match: (id) => /^(Shen2008|Cheung2004)/i.test(id),
  about: 'Many terms fit 24 patches closely: judge them by the leave-one-out error.',
};

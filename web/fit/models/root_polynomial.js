// Root-polynomial regression (Finlayson, Mackiewicz & Hurlbert 2015), degree 1–4.
export default {
  family: 'Root-polynomials',
  match: (id) => /^Finlayson2015/i.test(id),
  about: 'Finlayson et al. 2015: exposure-invariant; degree 2 is Guarnera et al. 2018 T2R (eq 15).',
};

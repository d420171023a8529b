// Root-polynomial regression (Finlayson, Mackiewicz & Hurlbert 2015), degree 1–4.
export default {
  family: 'Root-polynomials',
  match: (id) => /^Finlayson2015/i.test(id),
  about: 'Exposure-invariant; degree 2 is Guarnera T2R.',
};

// Guarnera et al. 2018 transforms T1, To and T2R (eqs 13–15), under the paper's names.
export default {
  family: 'Guarnera et al. 2018',
  match: (id) => /^Guarnera2018/i.test(id),
  about: 'T1 (eq 13), To (eq 14), T2R (eq 15); fitted by pattern search in the paper (objective "psm").',
};

// Guarnera et al. 2018 transforms T1, To and T2R (eqs 13–15), under the paper's names.
export default {
  family: 'Guarnera et al. 2018',
  match: (id) => /^Guarnera2018/i.test(id),
  about: 'The paper\'s T1, To and T2R; fitted by pattern search there (objective "psm").',
};

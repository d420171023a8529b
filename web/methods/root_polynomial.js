// Root-polynomial regression (Finlayson, Mackiewicz & Hurlbert 2015), degree 1-4; degree 2 is
// Guarnera et al. 2018's T2R (eq 15).
import { field, select } from '../lib/ui.js';

export default {
  match: (id) => /root/i.test(id) || /finlayson/i.test(id),
  label: 'Root-polynomial',
  about: 'Finlayson et al. 2015; degree 2 = Guarnera et al. 2018 T2R (eq 15). Exposure-invariant.',
  defaults: { degree: 2 },
  form(options, onChange) {
    const s = select([1, 2, 3, 4].map((d) => ({ value: String(d), label: `degree ${d}` })), String(options.degree ?? 2));
    s.addEventListener('change', () => onChange({ ...options, degree: Number(s.value) }));
    return field('Degree', s);
  },
};

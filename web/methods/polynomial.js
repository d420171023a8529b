// Polynomial expansions: Shen et al. 2008's 10-term vector (eq 23) and Cheung 2004's family.
import { h, field, select } from '../lib/ui.js';

export const CHEUNG_TERMS = [3, 5, 7, 8, 10, 11, 14, 16, 17, 19, 20, 22, 35];
export default {
  match: (id) => /(poly|cheung|shen)/i.test(id) && !/root/i.test(id),
  label: 'Polynomial',
  about: 'Shen et al. 2008 eq (23) (10 terms) or Cheung 2004 expansions (3–35 terms).',
  defaults: { terms: 10 },
  form(options, onChange) {
    if (/shen/i.test(this.id ?? '')) return null;
    const s = select(CHEUNG_TERMS.map((t) => ({ value: String(t), label: `${t} terms` })), String(options.terms ?? 10));
    s.addEventListener('change', () => onChange({ ...options, terms: Number(s.value) }));
    return field('Terms', s);
  },
};

// Options of the fitting objectives, with the engine's defaults (see models.hpp):
// "psm" Guarnera et al. 2018 Algorithm 2 (pattern search), "de2000" mean CIEDE2000 via NLopt.
import { h, field, select } from '../lib/ui.js';

const num = (label, value, onChange, attrs = {}) => {
  const i = h('input', { type: 'number', value, ...attrs });
  i.addEventListener('change', () => onChange(Number(i.value)));
  return field(label, i);
};

export const OBJECTIVE_OPTIONS = {
  psm: {
    defaults: { initialStep: 1, expansion: 2, contraction: 0.5, stepThreshold: 1e-6, maxIterations: 0 },
    form(o, set) {
      return [
        num('Initial step Δ₀', o.initialStep, (v) => set({ ...o, initialStep: v }), { step: 0.1, min: 0 }),
        num('Expansion α', o.expansion, (v) => set({ ...o, expansion: v }), { step: 0.1, min: 1 }),
        num('Contraction β', o.contraction, (v) => set({ ...o, contraction: v }), { step: 0.05, min: 0, max: 1 }),
        num('Step threshold', o.stepThreshold, (v) => set({ ...o, stepThreshold: v }), { step: 'any', min: 0 }),
        num('Max iterations (0: 100 × variables)', o.maxIterations, (v) => set({ ...o, maxIterations: v }), { step: 1, min: 0 }),
      ];
    },
  },
  de2000: {
    defaults: { algorithm: 'bobyqa', rms: false, maxEvaluations: 0 },
    form(o, set) {
      const alg = select([{ value: 'bobyqa', label: 'BOBYQA' }, { value: 'sbplx', label: 'Subplex' }], o.algorithm);
      alg.addEventListener('change', () => set({ ...o, algorithm: alg.value }));
      const rms = h('input', { type: 'checkbox', checked: !!o.rms });
      rms.addEventListener('change', () => set({ ...o, rms: rms.checked }));
      rms.id = 'de2000-rms';
      return [
        field('NLopt algorithm', alg),
        h('div', { class: 'check' }, rms, h('label', { for: rms.id }, 'Minimise the RMS instead of the mean')),
        num('Max evaluations (0: engine default)', o.maxEvaluations, (v) => set({ ...o, maxEvaluations: v }), { step: 1, min: 0 }),
      ];
    },
  },
};

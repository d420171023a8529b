// Reads summary errors out of a fit result, whatever nesting the engine uses:
// set = 'training' | 'loo' | 'heldOut'; stat = 'mean' | 'median' | 'p95' | 'max' | 'rms'.
import { pick } from './perpatch.js';

const SETS = {
  training: ['training', 'train', 'metrics.training', 'metrics.train'],
  loo: ['loo', 'leaveOneOut', 'looCV', 'metrics.loo', 'metrics.leaveOneOut', 'crossValidation'],
  heldOut: ['heldOut', 'held_out', 'test', 'metrics.heldOut'],
};

export function metric(result, set, stat = 'mean') {
  const src = { ...(result.fit ?? {}), ...(set === 'heldOut' && result.heldOut ? { heldOut: result.heldOut } : {}) };
  const paths = [];
  for (const s of SETS[set]) paths.push(`${s}.dE2000.${stat}`, `${s}.CIE2000.${stat}`, `${s}.dE00.${stat}`, `${s}.${stat}`);
  const v = pick(src, ...paths);
  return typeof v === 'number' ? v : NaN;
}

export const COLUMNS = [
  { key: 'train-mean', set: 'training', stat: 'mean', label: 'training mean' },
  { key: 'train-max', set: 'training', stat: 'max', label: 'training max' },
  { key: 'loo-mean', set: 'loo', stat: 'mean', label: 'leave-one-out mean' },
  { key: 'loo-max', set: 'loo', stat: 'max', label: 'leave-one-out max' },
  { key: 'held-mean', set: 'heldOut', stat: 'mean', label: 'held-out chart mean' },
];

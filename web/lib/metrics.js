// Summary errors of a result (the engine's Metrics): set = 'training' | 'loo' | 'heldOut';
// stat = 'mean' | 'median' | 'p95' | 'max' | 'rms' (CIEDE2000).
export function metric(result, set, stat = 'mean') {
  const m = set === 'heldOut' ? result.heldOut : result.fit?.evaluation?.[set];
  const v = m?.dE00?.[stat];
  return typeof v === 'number' ? v : NaN;
}

export const COLUMNS = [
  { key: 'train-mean', set: 'training', stat: 'mean', label: 'training mean' },
  { key: 'train-max', set: 'training', stat: 'max', label: 'training max' },
  { key: 'loo-mean', set: 'loo', stat: 'mean', label: 'leave-one-out mean' },
  { key: 'loo-max', set: 'loo', stat: 'max', label: 'leave-one-out max' },
  { key: 'held-mean', set: 'heldOut', stat: 'mean', label: 'held-out chart mean' },
];

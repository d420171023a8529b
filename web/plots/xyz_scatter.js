// Estimated vs reference X, Y, Z with the identity line (Guarnera et al. 2018, fig 10).
import { getPlot } from './common.js';
import { patchTitle } from '../lib/perpatch.js';

export function xyzScatterData(rows) {
  const out = [];
  for (const r of rows) for (const [c, e] of [['X', 'Xe'], ['Y', 'Ye'], ['Z', 'Ze']]) out.push({ channel: c, ref: r[c], est: r[e], fill: r.fill, row: r });
  return out;
}

export function xyzScatterPlot(rows, { width = 900, Plot = getPlot() } = {}) {
  const data = xyzScatterData(rows).filter((d) => Number.isFinite(d.ref) && Number.isFinite(d.est));
  const max = Math.max(1, ...data.map((d) => Math.max(d.ref, d.est))) * 1.05;
  return Plot.plot({
    width, height: 330, marginLeft: 48, marginBottom: 40, grid: true,
    fx: { label: null, domain: ['X', 'Y', 'Z'], tickFormat: (c) => `${c} (white Y = 100)` },
    x: { label: 'reference →', domain: [0, max] },
    y: { label: '↑ estimate', domain: [0, max] },
    marks: [
      Plot.line([[0, 0], [max, max]], { stroke: '#888', strokeDasharray: '4,3' }),
      Plot.dot(data, { fx: 'channel', x: 'ref', y: 'est', r: 4, fill: 'fill', stroke: '#222', strokeWidth: 0.6, title: (d) => `${d.channel}: reference ${d.ref.toFixed(2)}, estimate ${d.est.toFixed(2)}\n${patchTitle(d.row)}`, tip: true }),
      Plot.frame({ stroke: '#ccc' }),
    ],
  });
}

// CIELAB planes with reference -> estimate lines (Abed et al. 2013, fig 12): a*–L* and C*–L*.
import { getPlot } from './common.js';
import { patchTitle } from '../lib/perpatch.js';

/// rows from perPatch(); plane 'a' (a*–L*) or 'C' (C*–L*).
export function labPlanePlot(rows, plane = 'a', { width = 410, Plot = getPlot() } = {}) {
  const [h1, h2, name] = plane === 'a' ? ['a', 'ae', 'a*'] : ['C', 'Ce', 'C*ab'];
  const ok = rows.filter((r) => Number.isFinite(r[h1]) && Number.isFinite(r[h2]));
  const hi = Math.max(10, ...ok.map((r) => Math.max(Math.abs(r[h1]), Math.abs(r[h2])))) * 1.08;
  return Plot.plot({
    width, height: 410, marginLeft: 44, marginBottom: 38, grid: true,
    x: { label: `${name} (CIELAB, unitless) →`, domain: plane === 'a' ? [-hi, hi] : [0, hi] },
    y: { label: '↑ L* (CIELAB lightness)', domain: [0, 100] },
    marks: [
      plane === 'a' ? Plot.ruleX([0], { stroke: '#999' }) : null,
      Plot.link(ok, { x1: h1, y1: 'L', x2: h2, y2: 'Le', stroke: '#222', strokeWidth: 1.2 }),
      Plot.dot(ok, { x: h1, y: 'L', r: 5, fill: 'fill', stroke: '#222', strokeWidth: 0.7, title: patchTitle, tip: true }),
      Plot.dot(ok, { x: h2, y: 'Le', r: 2.5, fill: '#111', title: patchTitle }),
    ],
  });
}

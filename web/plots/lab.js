// CIELAB planes with reference -> estimate lines (Abed et al. 2013, fig 12): a*–L* and C*–L*; the
// a*–b* plane with each estimate's uncertainty ellipse (the bootstrap's).
import { getPlot } from './common.js';
import { ellipseOutlines } from './xy.js';
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

/// a*–b* plane: reference (dot) → estimate (small dot), and `ellipses` ([{id, cx, cy, cov, k}], as
/// xy.js's) around the estimates.
export function abPlanePlot(rows, ellipses = [], { width = 410, Plot = getPlot() } = {}) {
  const ok = rows.filter((r) => [r.a, r.b, r.ae, r.be].every(Number.isFinite));
  const outlines = ellipseOutlines(ellipses);
  const hi = Math.max(10, ...ok.map((r) => Math.max(Math.abs(r.a), Math.abs(r.b), Math.abs(r.ae), Math.abs(r.be))),
    ...outlines.map((p) => Math.max(Math.abs(p.x), Math.abs(p.y)))) * 1.08;
  return Plot.plot({
    width, height: width, marginLeft: 44, marginBottom: 38, grid: true,
    x: { label: 'a* (CIELAB) →', domain: [-hi, hi] },
    y: { label: '↑ b* (CIELAB)', domain: [-hi, hi] },
    marks: [
      Plot.ruleX([0], { stroke: '#999' }), Plot.ruleY([0], { stroke: '#999' }),
      Plot.link(ok, { x1: 'a', y1: 'b', x2: 'ae', y2: 'be', stroke: '#222', strokeWidth: 1.2 }),
      Plot.dot(ok, { x: 'a', y: 'b', r: 5, fill: 'fill', stroke: '#222', strokeWidth: 0.7, title: patchTitle, tip: true }),
      Plot.dot(ok, { x: 'ae', y: 'be', r: 2.5, fill: '#111', title: patchTitle }),
      outlines.length ? Plot.line(outlines, { x: 'x', y: 'y', z: 'id', stroke: '#c0392b', strokeWidth: 1.2, className: 'ellipse' }) : null,
    ],
  });
}

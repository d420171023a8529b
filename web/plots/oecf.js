// The fitted OECFs per channel and per exposure, Guarnera 2018 fig 5 style: the normalised
// camera response R′, G′, B′ (eq 7) of the training stimuli against their luminance Y (cd/m²),
// one panel per exposure {t, N, ISO}, log axes; the common eq (8) curve of each channel at that
// exposure's ε drawn through the points, and (dashed) the exposure's own fit of the reciprocity
// check. Parallel lines across panels = reciprocity holds. Pure function from arrays to SVG.
import { getPlot } from './common.js';

export const CHANNELS = [
  { id: 'R', colour: '#c0392b', symbol: 'circle' },
  { id: 'G', colour: '#2e8b3a', symbol: 'triangle' },
  { id: 'B', colour: '#2c5fb8', symbol: 'square' },
];

/// panels: the engine's OecfPanel list (fitAbsolute().panels) -> rows for the plot.
export function oecfRows(panels) {
  const points = [], curves = [], own = [];
  for (const p of panels) {
    for (let c = 0; c < 3; c++) {
      const ch = CHANNELS[c].id;
      p.point_Y[c].forEach((Y, i) => points.push({ exposure: p.label, channel: ch, Y, R: p.point_R[c][i] }));
      p.curve_Y[c].forEach((Y, i) => curves.push({ exposure: p.label, channel: ch, Y, R: p.curve_R[c][i] }));
      p.own_Y[c].forEach((Y, i) => { if (Y > 0) own.push({ exposure: p.label, channel: ch, Y, R: p.curve_R[c][i] }); });
    }
  }
  return { points, curves, own };
}

export function oecfPlot(panels, { width = 1100, height = 320, Plot = getPlot() } = {}) {
  const { points, curves, own } = oecfRows(panels);
  const ys = points.map((d) => d.Y), rs = points.map((d) => d.R);
  const x = [Math.min(...ys) / 1.5, Math.max(...ys) * 1.5];
  const y = [Math.min(...rs) / 1.5, Math.min(1.6, Math.max(...rs) * 1.5)];
  const inside = (d) => d.Y >= x[0] && d.Y <= x[1] && d.R >= y[0] && d.R <= y[1];
  const labels = panels.map((p) => p.label);
  const colour = { domain: CHANNELS.map((c) => c.id), range: CHANNELS.map((c) => c.colour), legend: true, label: 'channel' };
  return Plot.plot({
    width, height, marginLeft: 60, marginBottom: 40, marginTop: 44,
    fx: { domain: labels, label: null, padding: 0.08 },
    x: { type: 'log', domain: x, label: 'luminance Y (cd/m²) →', grid: true, ticks: 3, tickFormat: ',~g' },
    y: { type: 'log', domain: y, label: "↑ normalised R′, G′, B′ (eq 7)", grid: true, tickFormat: '~g' },
    color: colour,
    symbol: { domain: CHANNELS.map((c) => c.id), range: CHANNELS.map((c) => c.symbol) },
    marks: [
      Plot.frame({ stroke: '#ccc' }),
      Plot.line(curves.filter(inside), { x: 'Y', y: 'R', fx: 'exposure', z: 'channel', stroke: 'channel', strokeWidth: 1.5 }),
      Plot.line(own.filter(inside), { x: 'Y', y: 'R', fx: 'exposure', z: 'channel', stroke: 'channel', strokeWidth: 1, strokeDasharray: '3,3' }),
      Plot.dot(points, { x: 'Y', y: 'R', fx: 'exposure', stroke: 'channel', symbol: 'channel', r: 2.5, title: (d) => `${d.channel} at ${d.exposure}: Y ${d.Y.toFixed(1)} cd/m², ${d.channel}′ ${d.R.toFixed(4)}` }),
      Plot.ruleY([1], { stroke: '#999', strokeDasharray: '2,3' }),
    ],
  });
}

// The recovered inverse OECF of each channel (linearisation step; plots/oecf.js is the absolute mode's) against the grey-based one (Shen et al. 2008, Fig 5),
// with the stored values of the chart's patches as ticks under the curves. Pure function from
// arrays to SVG.
import { getPlot } from './common.js';

/// Channel colours (Okabe–Ito: told apart with colour-vision deficiencies too).
export const CHANNEL_COLOURS = { R: '#D55E00', G: '#009E73', B: '#0072B2' };
const KINDS = {
  estimated: { label: 'recovered by the chosen method', dash: null },
  'grey-based': { label: 'grey-based (a polynomial through the grey patches)', dash: '6,4' },
};

/// rows: [{channel: 'R'|'G'|'B', kind: 'estimated'|'grey-based', x, y}]; ticks: [{channel, x, id}]
/// (the patches' stored values / full scale, drawn below 0, one row of ticks per channel).
export function oecfPlot(rows, ticks, { width = 900, height = 440, xLabel = 'stored value / full scale →',
  yLabel = '↑ linear response (relative)', Plot = getPlot() } = {}) {
  const kinds = Object.keys(KINDS).filter((k) => rows.some((r) => r.kind === k));
  const finite = rows.map((r) => r.y).filter(Number.isFinite);
  const top = Math.max(1, ...finite) * 1.04, bottom = Math.min(0, ...finite);
  const span = top - bottom;
  const tickRow = { R: 0, G: 1, B: 2 };
  const tickY = (d, k) => bottom - span * (0.05 + 0.045 * tickRow[d.channel] + 0.035 * k);
  const legend = [...kinds.map((k) => ({ k, label: KINDS[k].label, dash: KINDS[k].dash, colour: '#333' })),
    ...Object.entries(CHANNEL_COLOURS).map(([c, colour]) => ({ k: c, label: `${c} channel`, dash: null, colour }))];
  const x0 = Math.min(0, ...rows.map((r) => r.x));
  const ly = (i) => top - span * 0.06 * (i + 0.5);
  return Plot.plot({
    width, height, marginLeft: 56, marginRight: 76, marginBottom: 44,
    x: { label: xLabel, domain: [x0, 1], grid: true },
    y: { label: yLabel, domain: [bottom - span * 0.2, top], grid: true },
    marks: [
      ...legend.map((d, i) => Plot.line([[x0 + 0.01, ly(i)], [x0 + 0.06, ly(i)]], { stroke: d.colour, strokeWidth: 2, strokeDasharray: d.dash })),
      Plot.text(legend, { x: x0 + 0.07, y: (d, i) => ly(i), text: 'label', textAnchor: 'start', fontSize: 11 }),
      ...kinds.map((k) => Plot.line(rows.filter((r) => r.kind === k), {
        x: 'x', y: 'y', z: 'channel', stroke: (d) => CHANNEL_COLOURS[d.channel], strokeWidth: 2, strokeDasharray: KINDS[k].dash,
        title: (d) => `${d.channel}, ${KINDS[d.kind].label}`,
      })),
      Plot.ruleX(ticks, { x: 'x', y1: (d) => tickY(d, 0), y2: (d) => tickY(d, 1), stroke: (d) => CHANNEL_COLOURS[d.channel], strokeWidth: 1.2,
        title: (d) => `${d.id}: ${d.channel} ${d.x.toFixed(4)}${d.note ? ` (${d.note})` : ''}` }),
      Plot.text(['R', 'G', 'B'].map((c) => ({ c, y: tickY({ channel: c }, 0.5) })), { x: 1, y: 'y', text: (d) => `${d.c} patches`, textAnchor: 'start', dx: 6, fontSize: 10 }),
      Plot.ruleY([0]),
    ],
  });
}

// Reflectance curves (reflectance factor vs wavelength) of a few patches in up to three versions —
// as measured by the instrument, as corrected for the capture geometry, and a second measurement —
// and per-patch ΔE00 bars with each patch's colour. Pure functions from arrays to SVG.
import { getPlot } from './common.js';

export const CURVE_STYLES = {
  measured: { label: 'as measured (instrument geometry)', dash: null },
  corrected: { label: 'corrected (capture geometry)', dash: '6,3' },
  target: { label: 'second measurement', dash: '1.5,2.5' },
};

/// rows: [{id, kind ('measured'|'corrected'|'target'), wavelength, value, colour, last}]; the
/// legend is drawn in data coordinates above the curves, so an exported plot keeps it.
/// `styles`: the kinds and their legend labels and dashes (default CURVE_STYLES).
export function reflectancePlot(rows, { width = 900, height = 380, Plot = getPlot(), styles = CURVE_STYLES } = {}) {
  const kinds = Object.keys(styles).filter((k) => rows.some((r) => r.kind === k));
  const top = Math.max(0.2, ...rows.map((r) => r.value)) * 1.05;
  const x0 = Math.min(...rows.map((r) => r.wavelength));
  const legend = kinds.map((k, i) => ({ k, y: top * (1 + 0.07 * (kinds.length - i)) }));
  return Plot.plot({
    width, height, marginLeft: 50, marginRight: 50,
    x: { label: 'wavelength λ (nm) →' },
    y: { label: '↑ reflectance factor R (fraction of the perfect diffuser)', domain: [0, top * (1 + 0.07 * (kinds.length + 0.6))], grid: true },
    marks: [
      ...legend.map(({ k, y }) => Plot.line([[x0 + 3, y], [x0 + 23, y]], { stroke: '#333', strokeWidth: 1.8, strokeDasharray: styles[k].dash })),
      Plot.text(legend, { x: x0 + 26, y: 'y', text: (d) => styles[d.k].label, textAnchor: 'start', fontSize: 11 }),
      ...kinds.map((k) => Plot.line(rows.filter((r) => r.kind === k), {
        x: 'wavelength', y: 'value', z: 'id', stroke: 'colour', strokeWidth: 1.8, strokeDasharray: styles[k].dash,
        title: (d) => `${d.id} ${styles[d.kind].label}`,
      })),
      Plot.text(rows.filter((r) => r.kind === kinds[0] && r.last), { x: 'wavelength', y: 'value', text: 'id', dx: 6, textAnchor: 'start', fill: '#333', fontSize: 11 }),
      Plot.ruleY([0]),
    ],
  });
}

/// rows: [{id, value, fill, title}] — one bar per patch, the patch's colour as the bar's fill.
export function patchBarsPlot(rows, { width = 900, height = 260, label = '↑ CIEDE2000 ΔE00', Plot = getPlot() } = {}) {
  const ids = rows.map((r) => r.id);
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 44,
    x: { domain: ids, label: 'patch', tickRotate: ids.length > 30 ? -90 : 0, tickFormat: ids.length > 60 ? (d, i) => (i % 2 ? '' : d) : undefined },
    y: { label, grid: true },
    marks: [
      Plot.barY(rows, { x: 'id', y: 'value', fill: 'fill', stroke: '#555', strokeWidth: 0.4, title: 'title' }),
      Plot.ruleY([0]),
    ],
  });
}

/// rows: [{id, before, after, fill}] — per patch a wide grey bar (before) and a narrow bar in the
/// patch's colour (after), on one CIEDE2000 axis.
export function beforeAfterBarsPlot(rows, { width = 900, height = 280, Plot = getPlot() } = {}) {
  const ids = rows.map((r) => r.id);
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 44,
    x: { domain: ids, label: 'patch', tickRotate: ids.length > 30 ? -90 : 0, tickFormat: ids.length > 60 ? (d, i) => (i % 2 ? '' : d) : undefined },
    y: { label: '↑ CIEDE2000 ΔE00', grid: true },
    marks: [
      Plot.barY(rows, { x: 'id', y: 'before', fill: '#d0d0d0', title: (d) => `${d.id}: ΔE00 ${d.before.toFixed(2)} before` }),
      Plot.barY(rows, { x: 'id', y: 'after', fill: 'fill', stroke: '#333', strokeWidth: 0.4, insetLeft: 1.5, insetRight: 1.5,
        title: (d) => `${d.id}: ΔE00 ${d.before.toFixed(2)} before, ${d.after.toFixed(2)} after` }),
      Plot.ruleY([0]),
    ],
  });
}

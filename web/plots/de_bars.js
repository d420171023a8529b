// Per-patch CIEDE2000 bars split into the ΔL/ΔC/ΔH terms, with each patch's colour under its bar.
// The bar's length is ΔE00; each segment's share is that term's share of ΔL'²+ΔC'²+ΔH'²
// (the terms as weighted in CIEDE2000; the small rotation term is spread over ΔC and ΔH).
import { getPlot } from './common.js';
import { patchTitle } from '../lib/perpatch.js';

export const TERM_COLOURS = { 'ΔL (lightness)': '#0072B2', 'ΔC (chroma)': '#E69F00', 'ΔH (hue)': '#CC79A7' };  // Okabe–Ito, CVD-safe

export function deSegments(rows) {
  const out = [];
  for (const r of rows) {
    const t = [r.dL, r.dC, r.dH].map((v) => (Number.isFinite(v) ? v * v : 0));
    const s = t[0] + t[1] + t[2];
    Object.keys(TERM_COLOURS).forEach((term, k) => out.push({ id: r.id, term, value: s > 0 ? (r.dE * t[k]) / s : (k === 0 ? r.dE : 0), row: r }));
  }
  return out;
}

export function deBarsPlot(rows, { width = 900, Plot = getPlot() } = {}) {
  const ids = rows.map((r) => r.id);
  const maxDE = Math.max(1, ...rows.map((r) => (Number.isFinite(r.dE) ? r.dE : 0)));
  const chipH = maxDE * 0.07;
  return Plot.plot({
    width, height: 340, marginLeft: 44, marginBottom: 40, marginTop: 60,
    x: { domain: ids, label: 'patch', tickRotate: ids.length > 30 ? -90 : 0 },
    y: { label: '↑ CIEDE2000 ΔE00', domain: [-chipH * 1.4, maxDE * 1.05], grid: true },
    color: { domain: Object.keys(TERM_COLOURS), range: Object.values(TERM_COLOURS) },
    marks: [
      // The legend is drawn inside the SVG so an exported plot keeps it.
      ...Object.entries(TERM_COLOURS).flatMap(([term, colour], k) => [
        Plot.dot([term], { frameAnchor: 'top-right', dx: -110, dy: -46 + 16 * k, fill: colour, symbol: 'square', r: 5 }),
        Plot.text([term], { frameAnchor: 'top-right', dx: -100, dy: -46 + 16 * k, text: (d) => d, textAnchor: 'start', fontSize: 11 }),
      ]),
      Plot.barY(deSegments(rows), { x: 'id', y: 'value', fill: 'term', title: (d) => `${d.term}: ${d.value.toFixed(2)} of ${patchTitle(d.row)}`, tip: true }),
      Plot.rect(rows, { x: 'id', y1: -chipH * 1.3, y2: -chipH * 0.2, fill: 'fill', stroke: '#444', strokeWidth: 0.5, title: patchTitle }),
      Plot.ruleY([0]),
    ],
  });
}

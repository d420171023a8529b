// Shared plot helpers: the Observable Plot handle, patch colours, and a <figure> wrapper with a
// caption and SVG/PNG export buttons for every plot.
import { exportSvg, exportPng } from './export.js';

/// Observable Plot (UMD global in the page; pass {Plot} in tests).
export const getPlot = () => globalThis.Plot;

/// sRGB triplet (0..1, gamma-encoded) -> CSS colour, clipped.
export function cssColour(r, g, b) {
  const c = (v) => Math.round(255 * Math.min(1, Math.max(0, v)));
  return `rgb(${c(r)}, ${c(g)}, ${c(b)})`;
}

/// Interleaved sRGB (3N, 0..1) -> CSS colours. Values above 1.5 are taken as 0..255.
export function cssColours(sRGB) {
  const n = sRGB.length / 3;
  let max = 0;
  for (const v of sRGB) max = Math.max(max, v);
  const s = max > 1.5 ? 1 / 255 : 1;
  return Array.from({ length: n }, (_, i) => cssColour(sRGB[3 * i] * s, sRGB[3 * i + 1] * s, sRGB[3 * i + 2] * s));
}

/// XYZ (3N interleaved) -> [{x, y}] chromaticities (CIE 15 eq 7.3; x = X/(X+Y+Z)).
export function xyFromXYZ(XYZ) {
  const out = [];
  for (let i = 0; i < XYZ.length; i += 3) {
    const s = XYZ[i] + XYZ[i + 1] + XYZ[i + 2];
    out.push(s > 0 ? { x: XYZ[i] / s, y: XYZ[i + 1] / s } : { x: NaN, y: NaN });
  }
  return out;
}

/// Wraps a plot in a figure with a caption and export buttons; `name` names the files.
export function figure(svg, { name, caption, className = '' }) {
  // Plot returns a <figure> when it adds legends: export the SVG that holds the marks.
  const root = svg.tagName.toLowerCase() === 'svg' ? svg
    : [...svg.querySelectorAll('svg')].find((s) => s.querySelector(':scope > g[aria-label]')) ?? svg.querySelector('svg');
  const fig = document.createElement('figure');
  fig.className = `plot ${className}`;
  fig.dataset.plot = name;
  fig.append(svg);
  const cap = document.createElement('figcaption');
  cap.textContent = caption ?? '';
  const tools = document.createElement('span');
  tools.className = 'plot-tools';
  for (const [label, fn] of [['SVG', exportSvg], ['PNG', exportPng]]) {
    const b = document.createElement('button');
    b.type = 'button';
    b.textContent = label;
    b.setAttribute('aria-label', `Download the ${caption ?? name} plot as ${label}`);
    b.addEventListener('click', () => fn(root, name));
    tools.append(b);
  }
  cap.append(' ', tools);
  fig.append(cap);
  return fig;
}

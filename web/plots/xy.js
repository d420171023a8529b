// CIE 1931 xy chromaticity diagram: spectral locus (closed by the purple line), the sRGB gamut,
// the patches, and optionally reference -> estimate arrows (Guarnera et al. 2018, fig 11 style).
import { getPlot } from './common.js';

/// sRGB primaries and D65 white, IEC 61966-2-1.
export const SRGB_GAMUT = [{ x: 0.64, y: 0.33 }, { x: 0.30, y: 0.60 }, { x: 0.15, y: 0.06 }, { x: 0.64, y: 0.33 }];
export const D65_xy = { x: 0.3127, y: 0.3290 };

/// Locus {wavelengths, x, y} -> closed polyline points and labelled wavelengths.
export function locusData(locus, labels = [460, 480, 490, 500, 520, 540, 560, 580, 600, 620, 700]) {
  const pts = [];
  for (let i = 0; i < locus.x.length; i++) {
    if (Number.isFinite(locus.x[i]) && Number.isFinite(locus.y[i])) pts.push({ x: locus.x[i], y: locus.y[i], nm: locus.wavelengths[i] });
  }
  const closed = pts.length ? [...pts, pts[0]] : pts;
  const ticks = labels.map((nm) => pts.find((p) => Math.abs(p.nm - nm) < 0.5)).filter(Boolean);
  return { line: closed, ticks };
}

/// points: [{id, x, y, fill, title}], arrows: [{id, x1, y1, x2, y2, stroke, title}]
/// Square domain around the points and arrow ends (with a margin), for a zoomed diagram.
export function zoomDomain(points, arrows, pad = 0.03) {
  const xs = [...points.map((p) => p.x), ...arrows.flatMap((a) => [a.x1, a.x2])].filter(Number.isFinite);
  const ys = [...points.map((p) => p.y), ...arrows.flatMap((a) => [a.y1, a.y2])].filter(Number.isFinite);
  if (!xs.length) return null;
  const x0 = Math.min(...xs) - pad, x1 = Math.max(...xs) + pad, y0 = Math.min(...ys) - pad, y1 = Math.max(...ys) + pad;
  const side = Math.max(x1 - x0, y1 - y0);
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  return { x: [cx - side / 2, cx + side / 2], y: [cy - side / 2, cy + side / 2] };
}

/// ellipses: [{id, cx, cy, cov: [[a, b], [b, c]], k}] -> closed outlines [{id, x, y}] (for a
/// line mark with z: 'id'): the points c + k·L·(cos t, sin t), L the Cholesky factor of cov, i.e.
/// the curve (p − c)ᵀ cov⁻¹ (p − c) = k². Ellipses whose covariance is not positive definite or not
/// finite are left out.
export function ellipseOutlines(ellipses, steps = 48) {
  const out = [];
  for (const e of ellipses) {
    const [[a, b], [, c]] = e.cov ?? [[NaN, NaN], [NaN, NaN]];
    const l11 = Math.sqrt(a), l21 = b / l11, l22 = Math.sqrt(c - l21 * l21);
    if (![l11, l21, l22, e.cx, e.cy, e.k].every(Number.isFinite) || !(l11 > 0) || !(l22 > 0)) continue;
    for (let s = 0; s <= steps; s++) {
      const t = (2 * Math.PI * s) / steps, u = Math.cos(t), v = Math.sin(t);
      out.push({ id: e.id, x: e.cx + e.k * l11 * u, y: e.cy + e.k * (l21 * u + l22 * v) });
    }
  }
  return out;
}

export function xyPlot({ locus, points = [], arrows = [], white, width = 460, observer = '1931', zoom = false, ellipses = [] }, { Plot = getPlot() } = {}) {
  const L = locus ? locusData(locus) : { line: [], ticks: [] };
  const marks = [
    Plot.line(L.line, { x: 'x', y: 'y', stroke: '#444', strokeWidth: 1.2 }),
    Plot.dot(L.ticks, { x: 'x', y: 'y', r: 1.5, fill: '#444' }),
    // Outside the locus, except where the blue-green limb runs along the y axis (490, 500 nm:
    // x < 0.06), where a label on the left would sit on the axis's tick labels: inside there.
    Plot.text(L.ticks.filter((d) => d.nm < 510 && d.x >= 0.06), { x: 'x', y: 'y', text: (d) => `${d.nm}`, dx: -6, textAnchor: 'end', fontSize: 9, fill: '#444' }),
    Plot.text(L.ticks.filter((d) => d.nm >= 510 || d.x < 0.06), { x: 'x', y: 'y', text: (d) => `${d.nm}`, dx: 6, textAnchor: 'start', fontSize: 9, fill: '#444' }),
    Plot.line(SRGB_GAMUT, { x: 'x', y: 'y', stroke: '#888', strokeDasharray: '4,3' }),
    // Above the green primary, inside the locus (beside the red one it crossed the locus near 615 nm).
    Plot.text([{ x: 0.30, y: 0.60 }], { x: 'x', y: 'y', text: () => 'sRGB', dy: -9, fontSize: 10, fill: '#666' }),
  ];
  if (white) marks.push(Plot.dot([white], { x: 'x', y: 'y', symbol: 'plus', r: 5, stroke: '#000', title: () => `reference white x=${white.x.toFixed(4)} y=${white.y.toFixed(4)}` }));
  if (arrows.length) {
    marks.push(Plot.arrow(arrows, { x1: 'x1', y1: 'y1', x2: 'x2', y2: 'y2', stroke: '#111', strokeWidth: 1, headLength: 5, title: 'title' }));
  }
  marks.push(Plot.dot(points, { x: 'x', y: 'y', r: 4.5, fill: 'fill', stroke: '#222', strokeWidth: 0.7, title: 'title', tip: true }));
  const outlines = ellipseOutlines(ellipses);
  if (outlines.length) marks.push(Plot.line(outlines, { x: 'x', y: 'y', z: 'id', stroke: '#c0392b', strokeWidth: 1.2, className: 'ellipse' }));
  const z = zoom ? zoomDomain(points, [...arrows, ...outlines.map((p) => ({ x1: p.x, y1: p.y, x2: p.x, y2: p.y }))]) : null;
  return Plot.plot({
    width, aspectRatio: 1, marginLeft: 44, marginBottom: 38, clip: zoom,
    x: { domain: z?.x ?? [0, 0.8], label: `x (CIE ${observer} chromaticity, unitless) →`, grid: true },
    y: { domain: z?.y ?? [0, 0.9], label: `↑ y (CIE ${observer} chromaticity, unitless)`, grid: true },
    marks,
  });
}

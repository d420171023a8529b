// Worker-side rendering of an XYZ image (display only): sRGB via display.js, and a false-colour
// map of Y through a 256-entry colour table the page supplies (e.g. viridis). Downsamples by an
// integer factor so the page receives at most ~maxSide pixels on the long side.
import { displayMatrix, encode } from './display.js';

const ENC = new Uint8ClampedArray(4096);
for (let i = 0; i < 4096; i++) ENC[i] = Math.round(255 * encode(i / 4095));

/// xyz: Float32Array(3 w h); white: [X, Y, Z] the profile's white (Y = 100 scale);
/// lut: Uint8Array(256 * 3); yMax: Y mapped to the top of the map (default: 99th percentile).
export function renderXYZ(xyz, width, height, { white, lut, maxSide = 1400, yMax } = {}) {
  const f = Math.max(1, Math.ceil(Math.max(width, height) / maxSide));
  const w = Math.floor(width / f), hgt = Math.floor(height / f);
  const M = displayMatrix(white);
  const srgb = new Uint8ClampedArray(w * hgt * 4);
  const ymap = new Uint8ClampedArray(w * hgt * 4);
  if (!yMax) yMax = percentileY(xyz, 0.99) || 1;
  for (let j = 0; j < hgt; j++) {
    for (let i = 0; i < w; i++) {
      const s = 3 * ((j * f) * width + i * f);
      const X = xyz[s], Y = xyz[s + 1], Z = xyz[s + 2];
      const o = 4 * (j * w + i);
      const r = M[0] * X + M[1] * Y + M[2] * Z, g = M[3] * X + M[4] * Y + M[5] * Z, b = M[6] * X + M[7] * Y + M[8] * Z;
      srgb[o] = ENC[Math.max(0, Math.min(4095, Math.round(r * 4095)))];
      srgb[o + 1] = ENC[Math.max(0, Math.min(4095, Math.round(g * 4095)))];
      srgb[o + 2] = ENC[Math.max(0, Math.min(4095, Math.round(b * 4095)))];
      srgb[o + 3] = 255;
      const k = Math.max(0, Math.min(255, Math.round((255 * Y) / yMax)));
      ymap[o] = lut[3 * k]; ymap[o + 1] = lut[3 * k + 1]; ymap[o + 2] = lut[3 * k + 2]; ymap[o + 3] = 255;
    }
  }
  return { width: w, height: hgt, factor: f, srgb, ymap, yMax };
}

/// Approximate percentile of Y over a strided subsample (fast, for the colour-map range).
export function percentileY(xyz, p) {
  const n = xyz.length / 3;
  const step = Math.max(1, Math.floor(n / 200000));
  const ys = [];
  for (let i = 0; i < n; i += step) { const y = xyz[3 * i + 1]; if (Number.isFinite(y)) ys.push(y); }
  ys.sort((a, b) => a - b);
  return ys[Math.min(ys.length - 1, Math.floor(p * ys.length))];
}

/// CIE 1976 L*a*b* of one XYZ against `white` (CIE 15:2004 eqs 8.1–8.3), for the read-out only.
export function labOf([X, Y, Z], white) {
  const f = (t) => (t > 216 / 24389 ? Math.cbrt(t) : (24389 / 27 * t + 16) / 116);
  const fx = f(X / white[0]), fy = f(Y / white[1]), fz = f(Z / white[2]);
  return [116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)];
}

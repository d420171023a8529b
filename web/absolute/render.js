// Display renders of the Absolute mode's maps (worker side, display only): the luminance Y in
// cd/m² through a 256-entry colour table (linear or log10 between two limits), and the
// dominant source exposure per pixel through one colour per exposure. Both downsample by an
// integer factor (nearest pixel) to at most ~maxSide pixels on the long side.

/// Pixels with no value (saturated in every exposure: NaN) are drawn in this colour.
export const NO_VALUE_RGB = [255, 255, 255];

/// The limits of the Y colour bar: [low, high] in cd/m²; log needs low > 0.
export function luminanceRange(low, high, log) {
  let hi = high > 0 ? high : 1;
  let lo = log ? (low > 0 ? low : hi * 1e-4) : 0;
  if (log && lo >= hi) lo = hi / 10;
  return [lo, hi];
}

/// xyz: Float32Array(3 w h), cd/m²; lut: Uint8Array(256 * 3).
export function renderLuminance(xyz, width, height, { lut, log = true, maxSide = 900, low, high }) {
  const f = Math.max(1, Math.ceil(Math.max(width, height) / maxSide));
  const w = Math.floor(width / f), hgt = Math.floor(height / f);
  const rgba = new Uint8ClampedArray(w * hgt * 4);
  const [lo, hi] = luminanceRange(low, high, log);
  const a = log ? Math.log10(lo) : lo, b = log ? Math.log10(hi) : hi, scale = 255 / (b - a);
  for (let j = 0; j < hgt; j++) {
    for (let i = 0; i < w; i++) {
      const Y = xyz[3 * ((j * f) * width + i * f) + 1];
      const o = 4 * (j * w + i);
      if (!Number.isFinite(Y)) { rgba[o] = NO_VALUE_RGB[0]; rgba[o + 1] = NO_VALUE_RGB[1]; rgba[o + 2] = NO_VALUE_RGB[2]; rgba[o + 3] = 255; continue; }
      const v = log ? (Y > 0 ? Math.log10(Y) : -Infinity) : Y;
      const t = (v - a) * scale;
      const k = t <= 0 ? 0 : t >= 255 ? 255 : (t + 0.5) | 0;
      rgba[o] = lut[3 * k]; rgba[o + 1] = lut[3 * k + 1]; rgba[o + 2] = lut[3 * k + 2]; rgba[o + 3] = 255;
    }
  }
  return { width: w, height: hgt, factor: f, rgba, range: [lo, hi], log };
}

/// source: Uint8Array(w h), exposure index or 255 (none); colours: [[r, g, b], ...] per exposure.
export function renderSource(source, width, height, { colours, maxSide = 900 }) {
  const f = Math.max(1, Math.ceil(Math.max(width, height) / maxSide));
  const w = Math.floor(width / f), hgt = Math.floor(height / f);
  const rgba = new Uint8ClampedArray(w * hgt * 4);
  for (let j = 0; j < hgt; j++) {
    for (let i = 0; i < w; i++) {
      const s = source[(j * f) * width + i * f];
      const c = s === 255 || !colours[s] ? NO_VALUE_RGB : colours[s];
      const o = 4 * (j * w + i);
      rgba[o] = c[0]; rgba[o + 1] = c[1]; rgba[o + 2] = c[2]; rgba[o + 3] = 255;
    }
  }
  return { width: w, height: hgt, factor: f, rgba };
}

// Worker-side rendering of an XYZ image (display only): sRGB through the engine's display matrix
// and sRGB encoding (displayMatrix, XYZToDisplaySRGB), and a false-colour
// map of Y through a 256-entry colour table the page supplies (e.g. viridis). Downsamples by an
// integer factor so the page receives at most ~maxSide pixels on the long side.

/// 4096-entry table of the sRGB encoding (linear 0..1 -> 0..255), taken from the engine: greys
/// t·white through XYZToDisplaySRGB give encode(t) in every channel.
export function encodingTable(T, white) {
  const xyz = new Float64Array(3 * 4096);
  for (let i = 0; i < 4096; i++) for (let k = 0; k < 3; k++) xyz[3 * i + k] = (i / 4095) * white[k];
  const rgb = T.XYZToDisplaySRGB(xyz, white);
  const enc = new Uint8ClampedArray(4096);
  for (let i = 0; i < 4096; i++) enc[i] = Math.round(255 * rgb[3 * i]);
  return enc;
}

/// xyz: Float32Array(3 w h); matrix: row-major XYZ -> linear sRGB (the engine's displayMatrix of
/// the profile's white); enc: encodingTable(); lut: Uint8Array(256 * 3) colour map;
/// yMax: Y mapped to the top of the map (the caller's: the engine's 99th percentile of ySample).
export function renderXYZ(xyz, width, height, { matrix: M, enc: ENC, lut, maxSide = 1400, yMax = 1 } = {}) {
  const f = Math.max(1, Math.ceil(Math.max(width, height) / maxSide));
  const w = Math.floor(width / f), hgt = Math.floor(height / f);
  const srgb = new Uint8ClampedArray(w * hgt * 4);
  const ymap = new Uint8ClampedArray(w * hgt * 4);
  const yScale = 255 / yMax;
  for (let j = 0; j < hgt; j++) {
    for (let i = 0; i < w; i++) {
      const s = 3 * ((j * f) * width + i * f);
      const X = xyz[s], Y = xyz[s + 1], Z = xyz[s + 2];
      const o = 4 * (j * w + i);
      const r = M[0] * X + M[1] * Y + M[2] * Z, g = M[3] * X + M[4] * Y + M[5] * Z, b = M[6] * X + M[7] * Y + M[8] * Z;
      srgb[o] = ENC[r <= 0 ? 0 : r >= 1 ? 4095 : (r * 4095 + 0.5) | 0];
      srgb[o + 1] = ENC[g <= 0 ? 0 : g >= 1 ? 4095 : (g * 4095 + 0.5) | 0];
      srgb[o + 2] = ENC[b <= 0 ? 0 : b >= 1 ? 4095 : (b * 4095 + 0.5) | 0];
      srgb[o + 3] = 255;
      const t = Y * yScale;
      const k = t <= 0 ? 0 : t >= 255 ? 255 : (t + 0.5) | 0;
      ymap[o] = lut[3 * k]; ymap[o + 1] = lut[3 * k + 1]; ymap[o + 2] = lut[3 * k + 2]; ymap[o + 3] = 255;
    }
  }
  return { width: w, height: hgt, factor: f, srgb, ymap, yMax };
}

/// Y of every k-th pixel (at most ~250 000 values), for the engine's quantile of the map's range.
export function ySample(xyz) {
  const n = xyz.length / 3, step = Math.max(1, Math.floor(n / 250000));
  const out = new Float64Array(Math.ceil(n / step));
  for (let i = 0, k = 0; i < n; i += step, k++) out[k] = xyz[3 * i + 1];
  return out;
}

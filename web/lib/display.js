// Display-only colour conversions (never used for measurement): XYZ relative to a white ->
// Bradford-adapted to D65 -> sRGB (IEC 61966-2-1), gamma-encoded and clipped to 0..1.
const BRADFORD = [0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296];
const BRADFORD_INV = inv3(BRADFORD);
const XYZ_TO_SRGB = [3.2404542, -1.5371385, -0.4985314, -0.9692660, 1.8760108, 0.0415560, 0.0556434, -0.2040259, 1.0572252];
export const D65 = [95.047, 100, 108.883];

function inv3(m) {
  const [a, b, c, d, e, f, g, h, i] = m;
  const A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const det = a * A + b * B + c * C;
  return [A, -(b * i - c * h), b * f - c * e, B, a * i - c * g, -(a * f - c * d), C, -(a * h - b * g), a * e - b * d].map((v) => v / det);
}
const mul = (m, v) => [m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2], m[6] * v[0] + m[7] * v[1] + m[8] * v[2]];
function matmul(a, b) {
  const o = new Array(9);
  for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) o[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return o;
}

/// 3x3 matrix taking XYZ (white `white`, Y_white scaled to 1) to linear sRGB.
export function displayMatrix(white = D65) {
  const w = white.map((v) => (100 * v) / white[1]);          // white with Y = 100
  const src = mul(BRADFORD, w), dst = mul(BRADFORD, D65);
  const D = [dst[0] / src[0], 0, 0, 0, dst[1] / src[1], 0, 0, 0, dst[2] / src[2]];
  const cat = matmul(BRADFORD_INV, matmul(D, BRADFORD));
  return matmul(XYZ_TO_SRGB, cat).map((v) => v / white[1]);  // white -> (1, 1, 1)
}

export const encode = (v) => (v <= 0.0031308 ? 12.92 * Math.max(0, v) : 1.055 * Math.pow(Math.min(v, 1), 1 / 2.4) - 0.055);

/// Interleaved XYZ (3N) -> interleaved gamma-encoded sRGB (3N), for swatches.
export function XYZ_to_display_sRGB(XYZ, white = D65) {
  const M = displayMatrix(white);
  const out = new Float64Array(XYZ.length);
  for (let i = 0; i < XYZ.length; i += 3) {
    const rgb = mul(M, [XYZ[i], XYZ[i + 1], XYZ[i + 2]]);
    for (let k = 0; k < 3; k++) out[i + k] = Math.min(1, encode(rgb[k]));
  }
  return out;
}

// Non-linear chart images made at test time from the example RAW (nothing binary is committed):
// the Passport DNG decoded by the engine to linear camera RGB, each channel scaled so that its
// white patch sits at 1/1.6 of full scale, encoded with gamma 1/2.2 (V = 255·(lin/S)^(1/2.2)), then
// written as a 16-bit TIFF (here, uncompressed baseline) or an 8-bit JPEG (by the browser's
// canvas encoder, quality 0.95). A 5 × 5 box mean first takes the DNG's pixel noise (σ/mean
// 10–20 %) down: averaging an encoded noisy value is not encoding the average (Jensen), and that
// bias, not the encoding, would otherwise dominate the comparison with the RAW's fit.
import fs from 'node:fs';
import path from 'node:path';
import { repoRoot } from './harness.mjs';

export const EXAMPLE = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));
export const GAMMA = 2.2;

/// {width, height, rgba8 (Uint8ClampedArray, 4 per pixel), rgb16 (Uint16Array, 3 per pixel), scale}.
export function encodedPassport(T) {
  const raw = T.decodeRaw(new Uint8Array(fs.readFileSync(path.join(repoRoot, 'examples/web', EXAMPLE.file))));
  try {
    const w = raw.width(), hgt = raw.height();
    const lin = raw.linearRGB();
    const s = T.sampleChart(raw, { chart: EXAMPLE.chart }, EXAMPLE.corners);
    const scale = [0, 1, 2].map((c) => 1.6 * Math.max(...s.patches.map((p) => p.mean[c])));
    // 5 × 5 box mean (edges: the pixels inside the image)
    const box = new Float32Array(lin.length);
    for (let y = 0; y < hgt; y++) {
      for (let x = 0; x < w; x++) {
        const acc = [0, 0, 0];
        let n = 0;
        for (let dy = -2; dy <= 2; dy++) {
          const yy = y + dy;
          if (yy < 0 || yy >= hgt) continue;
          for (let dx = -2; dx <= 2; dx++) {
            const xx = x + dx;
            if (xx < 0 || xx >= w) continue;
            const k = 3 * (yy * w + xx);
            acc[0] += lin[k]; acc[1] += lin[k + 1]; acc[2] += lin[k + 2]; n++;
          }
        }
        const k = 3 * (y * w + x);
        for (let c = 0; c < 3; c++) box[k + c] = acc[c] / n;
      }
    }
    const rgba8 = new Uint8ClampedArray(4 * w * hgt), rgb16 = new Uint16Array(3 * w * hgt);
    for (let i = 0; i < w * hgt; i++) {
      for (let c = 0; c < 3; c++) {
        const v = Math.min(1, Math.max(0, box[3 * i + c] / scale[c])) ** (1 / GAMMA);
        rgba8[4 * i + c] = Math.round(255 * v);
        rgb16[3 * i + c] = Math.round(65535 * v);
      }
      rgba8[4 * i + 3] = 255;
    }
    return { width: w, height: hgt, rgba8, rgb16, scale };
  } finally {
    raw.delete();
  }
}

/// A baseline little-endian TIFF: RGB, 16 bits per sample, uncompressed, one strip.
export function tiff16(width, height, rgb16) {
  const tags = [
    [256, 4, 1, width], [257, 4, 1, height], [258, 3, 3, 'bps'], [259, 3, 1, 1], [262, 3, 1, 2],
    [273, 4, 1, 'data'], [277, 3, 1, 3], [278, 4, 1, height], [279, 4, 1, rgb16.length * 2], [284, 3, 1, 1],
  ];
  const ifdAt = 8, ifdSize = 2 + 12 * tags.length + 4, bpsAt = ifdAt + ifdSize, dataAt = bpsAt + 6;
  const buf = Buffer.alloc(dataAt + rgb16.length * 2);
  buf.write('II', 0, 'latin1');
  buf.writeUInt16LE(42, 2);
  buf.writeUInt32LE(ifdAt, 4);
  buf.writeUInt16LE(tags.length, ifdAt);
  tags.forEach(([tag, type, count, value], i) => {
    const e = ifdAt + 2 + 12 * i;
    buf.writeUInt16LE(tag, e);
    buf.writeUInt16LE(type, e + 2);
    buf.writeUInt32LE(count, e + 4);
    const v = value === 'bps' ? bpsAt : value === 'data' ? dataAt : value;
    if (type === 3 && count === 1) buf.writeUInt16LE(v, e + 8); else buf.writeUInt32LE(v, e + 8);
  });
  buf.writeUInt32LE(0, ifdAt + 2 + 12 * tags.length);
  for (let k = 0; k < 3; k++) buf.writeUInt16LE(16, bpsAt + 2 * k);
  for (let i = 0; i < rgb16.length; i++) buf.writeUInt16LE(rgb16[i], dataAt + 2 * i);
  return buf;
}

/// An 8-bit JPEG of the RGBA pixels, encoded by the page's canvas (quality 0.95; no colour
/// management: an sRGB canvas stores the values it is given).
export async function jpegInPage(page, width, height, rgba8) {
  const b64 = await page.evaluate(async ([w, hgt, data]) => {
    const bytes = Uint8ClampedArray.from(atob(data), (ch) => ch.charCodeAt(0));
    const canvas = new OffscreenCanvas(w, hgt);
    canvas.getContext('2d').putImageData(new ImageData(bytes, w, hgt), 0, 0);
    const blob = await canvas.convertToBlob({ type: 'image/jpeg', quality: 0.95 });
    const out = new Uint8Array(await blob.arrayBuffer());
    let s = '';
    for (let i = 0; i < out.length; i += 0x8000) s += String.fromCharCode(...out.subarray(i, i + 0x8000));
    return btoa(s);
  }, [width, height, Buffer.from(rgba8.buffer, rgba8.byteOffset, rgba8.byteLength).toString('base64')]);
  return Buffer.from(b64, 'base64');
}

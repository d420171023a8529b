// Bad RAW files made at test time from the example Passport DNG, examples/web/passport.dng
// (nothing binary is committed): its one IFD is little-endian TIFF with an uncompressed, 14-bit
// packed CFA strip, so the width/height tags and the pixel bytes can be edited in place.
const TAGS = { width: 256, height: 257, rowsPerStrip: 278, stripOffsets: 273, bitsPerSample: 258, activeArea: 50829, defaultCropSize: 50720 };
const SIZE = { 1: 1, 2: 1, 3: 2, 4: 4, 5: 8, 7: 1, 10: 8 };

/// The entries of IFD 0: {tag: {type, count, at (offset of the value or of its data)}}.
export function ifd0(bytes) {
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (dv.getUint16(0, true) !== 0x4949 || dv.getUint16(2, true) !== 42) throw new Error('not a little-endian TIFF');
  const ifd = dv.getUint32(4, true);
  const out = {};
  for (let i = 0; i < dv.getUint16(ifd, true); i++) {
    const e = ifd + 2 + 12 * i;
    const type = dv.getUint16(e + 2, true), count = dv.getUint32(e + 4, true);
    const inline = (SIZE[type] ?? 1) * count <= 4;
    out[dv.getUint16(e, true)] = { type, count, at: inline ? e + 8 : dv.getUint32(e + 8, true) };
  }
  return { dv, entries: out };
}
function get(dv, { type, at }, k = 0) { return type === 3 ? dv.getUint16(at + 2 * k, true) : dv.getUint32(at + 4 * k, true); }
function set(dv, { type, at }, v, k = 0) { if (type === 3) dv.setUint16(at + 2 * k, v, true); else dv.setUint32(at + 4 * k, v, true); }

/// A copy of `dng` whose header claims width × height pixels (ActiveArea, RowsPerStrip and the
/// default crop follow, so the header is consistent with itself). The pixel data is not changed:
/// a smaller size decodes (the first rows, re-wrapped), a huge one must be refused.
export function withSize(dng, width, height, { keepBytes = dng.length } = {}) {
  const b = Uint8Array.from(dng.subarray(0, keepBytes));
  const { dv, entries: e } = ifd0(b);
  const w0 = get(dv, e[TAGS.width]), h0 = get(dv, e[TAGS.height]);
  set(dv, e[TAGS.width], width);
  set(dv, e[TAGS.height], height);
  if (e[TAGS.rowsPerStrip]) set(dv, e[TAGS.rowsPerStrip], height);
  const aa = e[TAGS.activeArea];   // top, left, bottom, right
  if (aa) {
    const [top, left, bottom, right] = [0, 1, 2, 3].map((k) => get(dv, aa, k));
    set(dv, aa, Math.min(bottom, height - (h0 - bottom)), 2);
    set(dv, aa, Math.min(right, width - (w0 - right)), 3);
    const crop = e[TAGS.defaultCropSize];
    if (crop) {
      set(dv, crop, Math.min(get(dv, crop, 0), get(dv, aa, 3) - left), 0);
      set(dv, crop, Math.min(get(dv, crop, 1), get(dv, aa, 2) - top), 1);
    }
  }
  return b;
}

/// A copy of `dng` with sensor rows [row0, row1) set to zero (below the black level: no signal).
export function withZeroRows(dng, row0, row1) {
  const b = Uint8Array.from(dng);
  const { dv, entries: e } = ifd0(b);
  const width = get(dv, e[TAGS.width]), bits = dv.getUint16(e[TAGS.bitsPerSample].at, true);
  const rowBytes = (width * bits) / 8;
  const start = get(dv, e[TAGS.stripOffsets]);
  b.fill(0, start + row0 * rowBytes, start + row1 * rowBytes);
  return b;
}

/// A flat field of the same camera and size as `dng`: sensor rows above `splitRow` filled with
/// bytes 0xAA, the rest with 0x55. In the 14-bit packed strip these read as alternating bits,
/// 10922 and 5461 DN: between the black level (2056) and the white level (15000) everywhere, so
/// every pixel has signal, and the two levels make the per-pixel gains differ from 1.
export function twoLevelFlat(dng, splitRow) {
  const b = Uint8Array.from(dng);
  const { dv, entries: e } = ifd0(b);
  const width = get(dv, e[TAGS.width]), bits = dv.getUint16(e[TAGS.bitsPerSample].at, true);
  const start = get(dv, e[TAGS.stripOffsets]);
  b.fill(0xAA, start, start + splitRow * ((width * bits) / 8));
  b.fill(0x55, start + splitRow * ((width * bits) / 8));
  return b;
}

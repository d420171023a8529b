// RAW pipeline through the wasm module: real files (same linear data as the native build), the
// JS shapes of decodeRaw / RawImage / sampleChart, calibration, and every bad input's code.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, readBytes, testPath, testFiles, throwsCode, repoRoot, assertSampleCsv } from './load.mjs';
import { assertPatchArrays } from './patch_arrays.mjs';

const PASSPORT = testFiles.passportDng;
const CR2 = testFiles.canon30dCr2;
const KDC = testFiles.kodakDc50Kdc;
// FNV-1a hashes of the linear data recorded from the native build (tests/core/capture/raw_test.cpp has
// the same numbers; when build/native exists the CLI is asked as well).
const FILES = [
  { file: PASSPORT, width: 867, height: 578, cfa: 'RGGB', hash: '7509a785b9c2f349' },
  { file: CR2, width: 1761, height: 1174, cfa: 'RGGB', hash: '2db01d705f5a94f5' },
  { file: KDC, width: 384, height: 256, cfa: 'GRBG', hash: 'ede561aaf256d76e' },
];
const nativeCli = path.join(repoRoot, 'build/native/core/tristim');
const passportJson = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));

function withRaw(T, bytes, fn) {
  const raw = T.decodeRaw(bytes);
  try { return fn(raw); } finally { raw.delete(); }
}

test('the three real RAW files decode with the native build\'s linear data', async () => {
  const T = await loadTristim();
  for (const c of FILES) {
    withRaw(T, readBytes(c.file), (raw) => {
      assert.equal(raw.width(), c.width, c.file);
      assert.equal(raw.height(), c.height, c.file);
      const m = raw.metadata();
      assert.equal(m.cfa_pattern, c.cfa);
      assert.equal(m.width, c.width);
      assert.equal(raw.linearHash(), c.hash, `${c.file}: wasm linear data differ from native`);
      assert.ok(fs.existsSync(nativeCli), `${nativeCli} not found: scripts/build.sh builds it`);
      {
        const native = JSON.parse(execFileSync(nativeCli, ['inspect', testPath(c.file)]).toString());
        assert.equal(native.linear_hash, raw.linearHash(), `${c.file}: native CLI vs wasm`);
        assert.equal(native.white_level, m.white_level);
        assert.deepEqual(native.black_level, m.black_level);
        // one field list: every member, name and form the module gives is what the CLI prints
        for (const k of Object.keys(m)) assert.deepEqual(m[k], native[k], `${c.file}: metadata.${k}`);
        assert.ok(Object.keys(m).length >= 33, `${c.file}: ${Object.keys(m).length} members`);
      }
      const rgb = raw.linearRGB();
      assert.ok(rgb instanceof Float32Array);
      assert.equal(rgb.length, c.width * c.height * 3);
      const mask = raw.saturationMask();
      assert.ok(mask instanceof Uint8Array);
      assert.equal(mask.length, c.width * c.height);
    });
  }
});

test('metadata is a plain object with exposure, levels and matrices', async () => {
  const T = await loadTristim();
  withRaw(T, readBytes(CR2), (raw) => {
    const m = raw.metadata();
    assert.equal(m.make, 'Canon');
    assert.equal(m.model, 'EOS 30D');
    assert.equal(m.iso, 640);
    assert.equal(m.f_number, 22);
    assert.equal(m.timestamp_iso, '2009-07-21T13:03:20');
    assert.equal(m.layout, 'bayer');
    assert.equal(m.rgb_cam.length, 9);
    assert.equal(m.black_level.length, 3);
  });
});

test('preview: RGBA bytes at most maxSide wide, scale maps back to the measurement image', async () => {
  const T = await loadTristim();
  withRaw(T, readBytes(PASSPORT), (raw) => {
    const pv = raw.preview(400);
    assert.equal(pv.scale, 3);
    assert.ok(pv.width <= 400 && pv.height <= 400);
    assert.ok(pv.rgba instanceof Uint8Array);
    assert.equal(pv.rgba.length, pv.width * pv.height * 4);
    assert.equal(pv.rgba[3], 255);
  });
});

test('sampleChart on the example Passport: 24 patches with ids A1..D6 and typed arrays', async () => {
  const T = await loadTristim();
  assert.ok(T.listChartLayouts().includes('passport'));
  withRaw(T, readBytes(PASSPORT), (raw) => {
    const s = T.sampleChart(raw, { chart: passportJson.chart }, new Float64Array(passportJson.corners), { area: 0.5 });
    assertPatchArrays(s, { count: 24, first: 'A1', last: 'D6' }, ['RGB', 'std', 'saturated_fraction']);
    assert.ok(s.n instanceof Int32Array);
    assert.equal(s.flags.length, 24);
    assert.ok(Array.isArray(s.flags[0]));
    assert.equal(s.patch_quads.length, 24 * 8);
    assert.equal(s.homography.length, 9);
    // D1 (white) is the brightest neutral; 3-argument form works too.
    assert.ok(fs.existsSync(nativeCli), `${nativeCli} not found: scripts/build.sh builds it`);
    {  // the native CLI samples the same numbers (CSV: 8 significant digits)
      const csv = execFileSync(nativeCli, ['sample', testPath(PASSPORT),
        '--chart', 'passport', '--corners', passportJson.corners.join(',')]).toString();
      assertSampleCsv(assert, csv, s);
    }
    const s3 = T.sampleChart(raw, { chart: 'passport' }, passportJson.corners);
    assert.deepEqual(Array.from(s3.RGB), Array.from(s.RGB));
    const G = (id) => s.RGB[3 * s.ids.indexOf(id) + 1];
    assert.ok(G('D1') > G('D2') && G('D2') > G('D3') && G('D3') > G('D6'));
  });
});

test('a dark frame and a flat field change what sampleChart reports; mismatches are coded', async () => {
  const T = await loadTristim();
  const img = T.decodeRaw(readBytes(PASSPORT));
  const same = T.decodeRaw(readBytes(PASSPORT));
  const other = T.decodeRaw(readBytes(KDC));
  try {
    const before = T.sampleChart(img, { chart: 'passport' }, passportJson.corners);
    const d = img.setDark([same], 'channel');
    assert.equal(d.frames, 1);
    assert.equal(d.mean.length, 3);
    const after = T.sampleChart(img, { chart: 'passport' }, passportJson.corners);
    assert.ok(Math.abs(after.RGB[1] - (before.RGB[1] - d.mean[1])) < 1e-3, `${after.RGB[1]} vs ${before.RGB[1] - d.mean[1]}`);
    img.clearDark();
    const r = img.setFlat(same, 'radial');
    assert.equal(r.p3, 1);
    assert.deepEqual(Object.keys(r), ['p1', 'p2', 'p3', 'centre_x', 'centre_y', 'r_scale', 'width', 'height', 'bins',
      'rms_residual', 'max_residual']);
    assert.ok(Number.isFinite(r.rms_residual));
    img.clearFlat();
    throwsCode(assert, () => img.setDark(other), 'FRAME_MISMATCH');
    throwsCode(assert, () => img.setFlat(other), 'FRAME_MISMATCH');
    const back = T.sampleChart(img, { chart: 'passport' }, passportJson.corners);
    assert.deepEqual(Array.from(back.RGB), Array.from(before.RGB));
  } finally {
    img.delete(); same.delete(); other.delete();
  }
});

test('bad RAW input: every case has its code and the module stays usable', async () => {
  const T = await loadTristim();
  throwsCode(assert, () => T.decodeRaw(new Uint8Array(0)), 'EMPTY_FILE');
  throwsCode(assert, () => T.decodeRaw(readBytes(PASSPORT).slice(0, 1 << 20)), 'RAW_TRUNCATED');
  // Images that are no RAW go to their own decoders (capture/image.hpp): bad ones have their codes.
  const jpeg = readBytes(testFiles.passportJpeg);
  throwsCode(assert, () => T.decodeRaw(jpeg.slice(0, jpeg.length >> 1)), 'IMAGE_CORRUPT');
  throwsCode(assert, () => T.decodeRaw(Uint8Array.from([71, 73, 70, 56, 57, 97, 1, 0, 1, 0, 0, 0, 0, 59])), 'IMAGE_UNSUPPORTED');  // GIF
  let seed = 42;
  const random = new Uint8Array(1000003).map(() => { seed = (seed * 1103515245 + 12345) >>> 0; return seed >>> 24; });
  throwsCode(assert, () => T.decodeRaw(random), 'RAW_UNSUPPORTED');
  // DNG headers claiming absurd / inconsistent sizes: patch the Passport's width and height tags.
  const patched = (w, h) => {
    const b = readBytes(PASSPORT).slice(0, 1 << 16);
    const dv = new DataView(b.buffer);
    const ifd = dv.getUint32(4, true);
    for (let i = 0; i < dv.getUint16(ifd, true); i++) {
      const e = ifd + 2 + 12 * i, tag = dv.getUint16(e, true), type = dv.getUint16(e + 2, true);
      const v = tag === 256 ? w : tag === 257 ? h : null;
      if (v !== null) { if (type === 3) dv.setUint16(e + 8, v, true); else dv.setUint32(e + 8, v, true); }
    }
    return b;
  };
  throwsCode(assert, () => T.decodeRaw(patched(60000, 60000)), 'RAW_TOO_LARGE');
  throwsCode(assert, () => T.decodeRaw(patched(6000, 4000)), 'RAW_TRUNCATED');
  withRaw(T, readBytes(PASSPORT), (raw) => {
    const L = { chart: 'passport' };
    throwsCode(assert, () => T.sampleChart(raw, L, [335, 291, 9649, 285, 649, 486, 328, 488]), 'CORNERS_OUTSIDE');
    throwsCode(assert, () => T.sampleChart(raw, L, [335, 291, 649, 285, 328, 488, 649, 486]), 'CORNERS_CROSSED');
    throwsCode(assert, () => T.sampleChart(raw, L, [10, 10, 20, 10, 20, 17, 10, 17]), 'PATCH_TOO_SMALL');
    throwsCode(assert, () => T.sampleChart(raw, { chart: 'nope' }, passportJson.corners), 'UNKNOWN_ID');
    throwsCode(assert, () => T.sampleChart(raw, L, [1, 2, 3]), 'INVALID_ARGUMENT');
    throwsCode(assert, () => raw.setFlat(raw, 'pixel'), 'FLAT_FIELD_ZERO');
    assert.equal(T.sampleChart(raw, L, passportJson.corners).ids.length, 24);  // still usable
  });
});

test('decodeRaw reads a JPEG, PNG or TIFF with its values as stored, and says so in the metadata', async () => {
  const T = await loadTristim();
  const jpeg = T.decodeRaw(readBytes(testFiles.passportJpeg));
  try {
    const m = jpeg.metadata();
    assert.equal(m.format, 'jpeg');
    assert.equal(m.encoding, 'stored');
    assert.equal(m.bits, 8);
    assert.equal(m.white_level, 255);
    assert.deepEqual(Array.from(m.saturation), [255, 255, 255]);
    const rgb = jpeg.linearRGB();
    assert.equal(rgb.length, 3 * jpeg.width() * jpeg.height());
    assert.ok(rgb.every((v) => Number.isInteger(v) && v >= 0 && v <= 255), 'stored 8-bit values, unchanged');
  } finally { jpeg.delete(); }
  // a 1 × 1 8-bit RGB PNG: integer values as stored
  const png = Uint8Array.from([137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 1, 0, 0, 0, 1, 8, 2, 0, 0, 0,
    144, 119, 83, 222, 0, 0, 0, 12, 73, 68, 65, 84, 120, 156, 99, 248, 207, 192, 0, 0, 3, 1, 1, 0, 201, 254, 146, 239, 0,
    0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130]);
  const p = T.decodeRaw(png);
  try {
    assert.equal(p.metadata().format, 'png');
    assert.equal(p.width(), 1);
    assert.deepEqual(Array.from(p.linearRGB()), Array.from(p.linearRGB()).map(Math.round));
  } finally { p.delete(); }
});

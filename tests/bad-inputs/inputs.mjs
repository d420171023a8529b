// The catalogue of bad inputs (catalogue.json) as bytes: each case is a committed file of the repo
// or a generator below applied to one (big inputs are made here, at test time, never committed).
// Walked by three runners with the same expectations: the CLI (run_cli.mjs, a native ctest), the
// wasm module (tests/wasm/bad_inputs.test.mjs) and the page (tests/web/catalogue.test.mjs).
//
// A case: {id, kind, name, from?, generate?, args?, expect, expect_cli?, expect_module?, note?}
//   kind     where it goes in: raw (the chart image input), reference (step 1's reference file),
//            patches (a camera-RGB table: the fit step's held-out file), profile (a profile JSON:
//            the export step's import), recipe (a recipe JSON; in the page embedded in a profile),
//            corners (chart corners on the example Passport DNG), dcp (a DNG camera profile:
//            `tristim inspect`, the module's readDcp, the export step's import), clf, cube, icc (a
//            Common LUT Format file, a .cube 3D LUT, an ICC profile: likewise, read by the file's name)
//   from     the base file, repo-relative (tests/support/test_files.mjs reads it)
//   generate a generator name below, applied to the base bytes (or to nothing) with `args`
//   runners  the runners that take the case (["cli"]: only the CLI reads such a file); absent: all
//   expect   the error code; expect_cli / expect_module when the CLI or the module (wasm and the
//            page) answer otherwise, expect_page when only the page does, with `note` saying why.
import fs from 'node:fs';
import path from 'node:path';
import { repoRoot, testFiles, readTestFile } from '../support/test_files.mjs';

export { repoRoot };
export const manifest = JSON.parse(fs.readFileSync(path.join(repoRoot, 'tests/bad-inputs/catalogue.json'), 'utf8'));
/// The Passport DNG the corner cases (and the page's example) use, repo-relative as in the
/// catalogue, and its good corners.
export const PASSPORT = path.relative(repoRoot, testFiles.passportDng);
export const passportCorners = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8')).corners;

/// The bytes of a base file (repo-relative, or absolute) in a fresh Uint8Array; a missing one
/// throws an error naming it.
export function readBase(rel) {
  return new Uint8Array(readTestFile(rel));
}

/// The absolute path of a base file (repo-relative, or absolute).
export const basePath = (rel) => (path.isAbsolute(rel) ? rel : path.join(repoRoot, rel));

const enc = new TextEncoder();
const dec = new TextDecoder();
const text = (s) => enc.encode(s);
/// Deterministic bytes (xorshift32), the same in every runner.
function noise(n, seed = 1) {
  const out = new Uint8Array(n);
  let x = seed >>> 0 || 1;
  for (let i = 0; i < n; i++) { x ^= x << 13; x >>>= 0; x ^= x >>> 17; x ^= x << 5; x >>>= 0; out[i] = x & 255; }
  return out;
}
const CRC_TABLE = Array.from({ length: 256 }, (_, n) => { let c = n; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; return c >>> 0; });
function crc32(bytes) { let c = 0xffffffff; for (const b of bytes) c = CRC_TABLE[(c ^ b) & 255] ^ (c >>> 8); return (c ^ 0xffffffff) >>> 0; }

/// IFD 0 entries of a little-endian TIFF/DNG: {tag: {type, count, at}} (at = where the value is).
function ifd0(b) {
  const dv = new DataView(b.buffer, b.byteOffset, b.byteLength);
  const ifd = dv.getUint32(4, true);
  const sizes = { 1: 1, 2: 1, 3: 2, 4: 4, 5: 8, 7: 1, 10: 8, 11: 4, 12: 8 };
  const out = {};
  for (let i = 0; i < dv.getUint16(ifd, true); i++) {
    const e = ifd + 2 + 12 * i;
    const type = dv.getUint16(e + 2, true), count = dv.getUint32(e + 4, true);
    out[dv.getUint16(e, true)] = { type, count, at: (sizes[type] ?? 1) * count <= 4 ? e + 8 : dv.getUint32(e + 8, true), entry: e };
  }
  return { dv, ifd, entries: out };
}

/// Generators: (base bytes or null, args) -> Uint8Array.
export const generators = {
  empty: () => new Uint8Array(0),
  text: (_, { value, repeat = 1 }) => text(value.repeat(repeat)),
  noise: (_, { size, seed = 1 }) => noise(size, seed),
  zeros: (_, { size }) => new Uint8Array(size),
  head: (b, { bytes, fraction }) => b.slice(0, bytes ?? Math.floor(b.length * fraction)),
  /// Overwrite bytes at an offset (hex string) — magic numbers, IFD offsets.
  patch: (b, { at, hex }) => { const o = b.slice(); for (let i = 0; i < hex.length / 2; i++) o[at + i] = parseInt(hex.substr(2 * i, 2), 16); return o; },
  /// Set IFD-0 tags of a little-endian DNG/TIFF: {tag: value}. Sizes of 0 or absurd ones.
  tiffTags: (b, { tags }) => {
    const o = b.slice();
    const { dv, entries } = ifd0(o);
    for (const [tag, v] of Object.entries(tags)) {
      const e = entries[tag];
      if (!e) throw new Error(`tag ${tag} not in IFD 0`);
      if (e.type === 3) dv.setUint16(e.at, v, true); else dv.setUint32(e.at, v, true);
    }
    return o;
  },
  /// A PNG whose IHDR claims width × height (CRC recomputed, so only the size is wrong).
  pngSize: (b, { width, height }) => {
    const o = b.slice();
    const dv = new DataView(o.buffer);
    dv.setUint32(16, width);
    dv.setUint32(20, height);
    dv.setUint32(29, crc32(o.subarray(12, 29)));
    return o;
  },
  /// Text edits of a text base: [[regex source, flags, replacement], ...].
  replace: (b, { edits }) => {
    let s = dec.decode(b);
    for (const [re, flags, to] of edits) {
      const next = s.replace(new RegExp(re, flags), to);
      if (next === s) throw new Error(`catalogue edit /${re}/ changed nothing`);
      s = next;
    }
    return text(s);
  },
  /// A patch table of `rows` data rows (ids P1..Pn) and `columns` numeric columns.
  table: (_, { rows, columns = 3, header }) => {
    const names = header ?? Array.from({ length: columns }, (_, i) => `C${i + 1}`);
    const parts = ['patch,' + names.join(',') + '\n'];
    const row = Array.from({ length: names.length }, (_, i) => (10 + i) / 4).join(',');
    for (let i = 1; i <= rows; i++) parts.push(`P${i},${row}\n`);
    return text(parts.join(''));
  },
  /// `bytes` bytes of well-formed CSV rows (huge file).
  bigCsv: (_, { bytes }) => {
    const line = 'A1,11.25,22.5,33.75\n';
    return text('patch,X,Y,Z\n' + line.repeat(Math.ceil(bytes / line.length)));
  },
  /// JSON edits of a JSON base: set (or delete with null) dotted paths; `wrap` puts the result in
  /// another document's field.
  json: (b, { set = {}, remove = [] }) => {
    const j = JSON.parse(dec.decode(b));
    for (const [p, v] of Object.entries(set)) {
      const keys = p.split('.');
      let o = j;
      for (const k of keys.slice(0, -1)) o = o[k];
      o[keys.at(-1)] = v;
    }
    for (const p of remove) {
      const keys = p.split('.');
      let o = j;
      for (const k of keys.slice(0, -1)) o = o[k];
      delete o[keys.at(-1)];
    }
    return text(JSON.stringify(j, null, 1));
  },
  /// A JSON base with an extra field holding a huge array / string / deep nesting.
  jsonBig: (b, { field, array, string, depth, padBytes }) => {
    const s = dec.decode(b).trimEnd();
    if (!s.endsWith('}')) throw new Error('jsonBig needs an object');
    let v;
    if (array) v = '[' + Array(array).fill('0').join(',') + ']';
    else if (string) v = '"' + 'x'.repeat(string) + '"';
    else if (depth) v = '['.repeat(depth) + ']'.repeat(depth);
    else if (padBytes) v = '"' + ' '.repeat(16) + '"' + ' '.repeat(padBytes);
    return text(s.slice(0, -1) + `, "${field}": ${v}}`);
  },
};

/// Every case with its bytes: [{...case, bytes: Uint8Array}]. `filter(case)` selects; `where`
/// ('cli' or 'module', the wasm module and the page) leaves out the cases whose runners exclude it.
export function materialise(filter = () => true, where = 'module') {
  return manifest.cases.filter((c) => (!c.runners || c.runners.includes(where)) && filter(c)).map((c) => {
    const base = c.from ? readBase(c.from) : null;
    let bytes = base;
    if (c.generate) {
      const g = generators[c.generate];
      if (!g) throw new Error(`${c.id}: unknown generator ${c.generate}`);
      bytes = g(base, c.args ?? {});
    }
    if (!bytes) throw new Error(`${c.id}: neither from nor generate`);
    return { ...c, bytes };
  });
}

/// The expected code of a case in a runner: 'cli' or 'module' (wasm and the page).
export const expected = (c, where) =>
  (where === 'cli' ? c.expect_cli : where === 'page' ? c.expect_page ?? c.expect_module : c.expect_module) ?? c.expect;

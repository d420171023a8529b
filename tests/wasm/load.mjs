// Loads the built wasm module for node --test suites (build/wasm/site/tristim.mjs by default;
// TRISTIM_WASM_DIR overrides), and reads the test files (tests/support/test_files.mjs).
import path from 'node:path';
import fs from 'node:fs';
import { pathToFileURL } from 'node:url';
import { repoRoot, testFiles, readTestFile } from '../support/test_files.mjs';

export { repoRoot, testFiles };
export const siteDir = process.env.TRISTIM_WASM_DIR || path.join(repoRoot, 'build/wasm/site');

let cached = null;
export async function loadTristim() {
  if (!cached) {
    const file = path.join(siteDir, 'tristim.mjs');
    if (!fs.existsSync(file)) throw new Error(`${file} not found: build first (bash scripts/build.sh)`);
    const create = (await import(pathToFileURL(file).href)).default;
    cached = await create();
  }
  return cached;
}

/// Bytes of a test file (a path of testFiles, or repository-relative) in a fresh Uint8Array. A
/// missing file throws an error naming it: the test fails, it never skips.
export function readBytes(file) {
  return new Uint8Array(readTestFile(file));
}

/// The absolute path of a test file (a path of testFiles, or repository-relative) to give a command
/// line, once it is known to exist (a missing file throws as readBytes).
export function testPath(file) {
  readTestFile(file);
  return path.isAbsolute(file) ? file : path.join(repoRoot, file);
}

/// Text of a test file (a path of testFiles, or repository-relative), as readBytes.
export function readText(file) {
  return new TextDecoder().decode(readTestFile(file));
}

/// Asserts that fn() throws an Error whose .code is `code`.
export function throwsCode(assert, fn, code) {
  assert.throws(fn, (e) => {
    assert.equal(e.code, code, `expected code ${code}, got ${e.code}: ${e.message}`);
    return true;
  });
}

/// Asserts that `tristim sample`'s CSV (8 significant digits) holds the module's sampleChart result
/// `s`: the header, each row's patch id, R, G, B within 1e-6 relative, pixels averaged and flags.
export function assertSampleCsv(assert, csvText, s) {
  const csv = csvText.trim().split('\n');
  assert.equal(csv[0], 'patch,R,G,B,R_std,G_std,B_std,n,flags');
  assert.equal(csv.length - 1, s.ids.length);
  csv.slice(1).forEach((line, i) => {
    const cells = line.split(',');
    assert.equal(cells[0], s.ids[i]);
    for (let c = 0; c < 3; c++) {
      const a = Number(cells[1 + c]), b = s.RGB[3 * i + c];
      assert.ok(Math.abs(a - b) <= 1e-6 * Math.abs(b), `${s.ids[i]} channel ${c}: CLI ${a} vs module ${b}`);
    }
    assert.equal(Number(cells[7]), s.n[i], `${s.ids[i]}: pixels averaged`);
    assert.equal(cells[8], s.flags[i].join(';'));
  });
}

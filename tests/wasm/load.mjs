// Loads the built wasm module for node --test suites (build/wasm/site/tristim.mjs by default;
// TRISTIM_WASM_DIR overrides). Also locates ../shared/data for tests that need it.
import path from 'node:path';
import fs from 'node:fs';
import { fileURLToPath, pathToFileURL } from 'node:url';

export const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const siteDir = process.env.TRISTIM_WASM_DIR || path.join(repoRoot, 'build/wasm/site');
export const sharedData = process.env.TRISTIM_SHARED_DATA || path.resolve(repoRoot, '../shared/data');

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

/// Bytes of a shared/data file; throws a clear message when shared data is missing.
export function readShared(relative) {
  const file = path.join(sharedData, relative);
  if (!fs.existsSync(file))
    throw new Error(`this test needs the project's shared data, not found at ${file} (set TRISTIM_SHARED_DATA)`);
  return new Uint8Array(fs.readFileSync(file));
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

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

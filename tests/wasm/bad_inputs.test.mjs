// The bad-input catalogue (tests/bad-inputs/catalogue.json) through the wasm module: each case
// goes to the binding the page's worker uses for that kind of input, and must throw an Error with
// the expected .code (expect_module, else expect). The module must still work after all of them.
import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim } from './load.mjs';
import { materialise, expected, readBase, PASSPORT, passportCorners } from '../bad-inputs/inputs.mjs';

const dec = new TextDecoder();

/// Runs one case; returns the code it threw, or 'OK'.
function run(T, c, passport) {
  try {
    switch (c.kind) {
      case 'raw': {  // as the page: decode (any image, by its bytes), then find the chart
        const raw = T.decodeRaw(c.bytes);
        try { T.detectCharts(raw); } finally { raw.delete(); }
        break;
      }
      case 'reference': T.parseReferenceFile(dec.decode(c.bytes), c.name, 'D50', '1931'); break;
      case 'patches': T.parsePatchFile(dec.decode(c.bytes), c.name); break;
      case 'profile': T.profileFromJson(dec.decode(c.bytes)); break;
      case 'recipe': T.recipeFromJson(dec.decode(c.bytes)); break;
      case 'dcp': T.readDcp(c.bytes); break;  // the reader the export step's import uses
      case 'link': T.reproduceLink(dec.decode(c.bytes)); break;  // what the Share step's Open calls
      case 'project': T.openProject(c.bytes); break;            // the Share step's project import
      case 'clf': T.readClf(dec.decode(c.bytes)); break;  // likewise for a CLF
      case 'cube': T.readCubeHeader(dec.decode(c.bytes), c.name); break;  // the export step's .cube and ICC import
      case 'icc': T.readIccHeader(c.bytes, c.name); break;
      case 'corners': T.sampleChart(passport, { chart: 'passport' }, c.corners); break;
      default: throw new Error(`${c.id}: unknown kind ${c.kind}`);
    }
    return 'OK';
  } catch (e) {
    if (!e.code) throw e;  // not a coded tristim error: a finding
    return e.code;
  }
}

test('every catalogue case gives its code in the wasm module, and the module stays usable', async () => {
  const T = await loadTristim();
  const passport = T.decodeRaw(readBase(PASSPORT));
  const cases = materialise();
  assert.ok(cases.length >= 60, `${cases.length} cases`);
  const wrong = [];
  const t0 = Date.now();
  try {
    for (const c of cases) {
      const got = run(T, c, passport);
      if (got !== expected(c, 'module')) wrong.push(`${c.id}: expected ${expected(c, 'module')}, got ${got}`);
    }
    console.log(`${cases.length} catalogue cases in the module, ${((Date.now() - t0) / 1000).toFixed(1)} s`);
    assert.deepEqual(wrong, []);
    // Still usable: the good Passport samples its 24 patches.
    assert.equal(T.sampleChart(passport, { chart: 'passport' }, passportCorners).ids.length, 24);
  } finally {
    passport.delete();
  }
});

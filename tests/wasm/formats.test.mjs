// The engine's readers of .cube and ICC headers (tristim/profile/headers.hpp) in the module: the
// module's own exports read back, results in the form of their field lists, refusals coded.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { loadTristim, repoRoot, throwsCode } from './load.mjs';

test('formats: .cube headers (a plain LUT, a Resolve shaper), refusals coded', async () => {
  const T = await loadTristim();
  const rows8 = '0 0 0\n'.repeat(8);
  assert.deepEqual(T.readCubeHeader(`TITLE "t"\nLUT_3D_SIZE 2\n${rows8}`, 't.cube'),
    { title: 't', size: 2, shaper_size: 0, entries: 8, domain_min: [0, 0, 0], domain_max: [1, 1, 1] });
  const shaped = T.readCubeHeader(`LUT_1D_SIZE 3\nLUT_1D_INPUT_RANGE 0 1\nLUT_3D_SIZE 2\n${'0 0 0\n'.repeat(3)}${rows8}`, 's.cube');
  assert.deepEqual([shaped.size, shaped.shaper_size, shaped.entries], [2, 3, 8]);
  throwsCode(assert, () => T.readCubeHeader('LUT_3D_SIZE 2\n0 0 0\n', 'short.cube'), 'PARSE_ERROR');
  throwsCode(assert, () => T.readCubeHeader('LUT_3D_SIZE 2\n0 0 x\n', 'bad.cube'), 'PARSE_ERROR');
});

test('formats: ICC headers of the engine\'s export; short, unsigned and mis-sized bytes refused', async () => {
  const T = await loadTristim();
  // the engine's ICC export of a 3 × 3 profile (the fuzz seed): a v4 scanner profile, RGB -> PCS
  const icc = new Uint8Array(fs.readFileSync(path.join(repoRoot, 'tests/fuzz/corpus/icc/matrix-3x3.icc')));
  const hd = T.readIccHeader(icc, 'matrix-3x3.icc');
  assert.deepEqual(Object.keys(hd), ['size', 'version', 'device_class', 'colour_space', 'pcs', 'tags', 'description']);
  assert.equal(hd.size, icc.length);
  assert.match(hd.version, /^4\./);
  assert.equal(hd.device_class, 'scnr');
  assert.equal(hd.colour_space, 'RGB');
  assert.ok(hd.tags.includes('desc') && hd.tags.includes('rXYZ'), hd.tags.join(' '));
  throwsCode(assert, () => T.readIccHeader(new Uint8Array(10), 'x.icc'), 'PARSE_ERROR');
  const fake = new Uint8Array(144);
  new DataView(fake.buffer).setUint32(0, 144);
  fake.set([0x61, 0x63, 0x73, 0x70], 36);
  throwsCode(assert, () => T.readIccHeader(fake.subarray(0, 140), 'cut.icc'), 'PARSE_ERROR');
  fake[36] = 0;
  throwsCode(assert, () => T.readIccHeader(fake, 'unsigned.icc'), 'PARSE_ERROR');
});

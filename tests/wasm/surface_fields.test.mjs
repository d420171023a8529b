// The surface stage's results cross by their field lists (core/src/surface/fields.cpp): the
// module's fitSurface, fitSurfaceJoint and surfaceTable4 give the objects `tristim surface fit /
// joint / table4 --json` prints — the same members in the same order (fitSurface adds the spectra
// the page draws), the same numbers to a stated tolerance (native and wasm optimise separately).
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, readText, testPath, repoRoot } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const SCI = 'examples/web/sg_d8_sci_coolpi.csv';
const SG_45 = 'core/data/charts/colorcheckerSG_before_nov2014_reflectance_380-730_10nm.csv';
const TOL = 1e-6;   // relative, per number

const cli = (...args) => JSON.parse(execFileSync(CLI, ['surface', ...args, '--json'], { encoding: 'utf8' }));

/// Same members in the same order, numbers within TOL (relative), a --surface text by its
/// method and coefficients; the path of the first difference in the message.
function same(a, b, where = '') {
  if (typeof a === 'number' && typeof b === 'number') {
    assert.ok(Math.abs(a - b) <= TOL * Math.max(1, Math.abs(a)), `${where}: module ${a}, CLI ${b} (tolerance ${TOL})`);
  } else if (where.endsWith('.surface') && typeof a === 'string') {
    const [ma, pa = ''] = a.split(':'), [mb, pb = ''] = b.split(':');
    assert.equal(ma, mb, where);
    const nums = (p) => Object.fromEntries(p.split(',').filter(Boolean).map((kv) => kv.split('=')).map(([k, v]) => [k, Number(v)]));
    same(nums(pa), nums(pb), where + '(coefficients)');
  } else if (a && typeof a === 'object' && b && typeof b === 'object') {
    assert.deepEqual(Object.keys(a), Object.keys(b), `${where}: members`);
    for (const k of Object.keys(a)) same(a[k], b[k], `${where}.${k}`);
  } else {
    assert.deepEqual(a, b, where);
  }
}

test('surfaceTable4: each cell is the object tristim surface table4 --json prints', async () => {
  const T = await loadTristim();
  const cells = T.surfaceTable4('Nikon_D850', 'D50', 0.001, 1);
  const printed = cli('table4', '--camera', 'Nikon_D850', '--illuminant', 'D50', '--noise', '0.001', '--seed', '1');
  assert.equal(cells.length, printed.cells.length);
  same(cells, printed.cells, 'cells');
  const c = cells.find((x) => x.method === 'corrected-3x3');
  assert.deepEqual(Object.keys(c.dE00), ['min', 'median', 'mean', 'p95', 'max', 'rms', 'std']);   // Summary's own list
  assert.ok(c.mu > 0 && !('mu' in cells.find((x) => x.method === 'matrix-3x3')), 'mu only for corrected-3x3');
});

test('fitSurface: the object tristim surface fit --json prints, with the spectra', async () => {
  const T = await loadTristim();
  const from = T.parsePatchFile(readText(SCI), 'sci.csv').spectra, to = T.parsePatchFile(readText(SG_45), 'sg.csv').spectra;
  const r = T.fitSurface('scaler-offset', from, to, { range_min: 400, range_max: 700 }, 'D50');
  const printed = cli('fit', '--from', testPath(SCI), '--to', testPath(SG_45), '--method', 'scaler-offset', '--range', '400-700');
  const { measured, corrected, target, ...figures } = r;
  same(figures, printed, 'fit');
  assert.equal(corrected.values.length, r.patches.length);
  assert.deepEqual(target.names, r.patches.map((p) => p.patch));
  assert.equal(measured.values[0].length, r.wavelengths.length);
});

test('fitSurfaceJoint: the object tristim surface joint --json prints', async () => {
  const T = await loadTristim();
  const reflectances = T.chartReflectances('sg140-2005');
  const ids = reflectances.names.slice(0, 24);
  const rgb = ids.flatMap((_, i) => [0.1 + ((i * 37) % 80) / 100, 0.1 + ((i * 53) % 80) / 100, 0.1 + ((i * 71) % 80) / 100]);
  const spectra = { ...reflectances, names: ids, values: reflectances.values.slice(0, 24) };
  const r = T.fitSurfaceJoint('scaler-offset', rgb, spectra, { white_RGB: [0.9, 0.95, 0.92] }, 'D50');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-joint-'));
  try {
    const file = path.join(dir, 'rgb.csv');
    fs.writeFileSync(file, ['patch,R,G,B', ...ids.map((id, i) => [id, ...rgb.slice(3 * i, 3 * i + 3)].join(','))].join('\n') + '\n');
    const printed = cli('joint', '--rgb', file, '--reflectances', testPath(SG_45), '--method', 'scaler-offset', '--white-rgb', '0.9,0.95,0.92');
    same(r, printed, 'joint');
  } finally { fs.rmSync(dir, { recursive: true, force: true }); }
});

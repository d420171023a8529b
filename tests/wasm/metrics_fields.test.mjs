// Metrics, Summary and PatchErrors cross by their field lists (tristim/evaluation/evaluation.hpp):
// a Metrics object is what `tristim evaluate` prints under "metrics" (the summaries, then the
// per-patch errors as `patches`, without the ids), a figure that is not a number is null in both.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, repoRoot } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const table = (head, ids, m) => [head, ...ids.map((id, i) => [id, m[3 * i], m[3 * i + 1], m[3 * i + 2]].join(','))].join('\n') + '\n';

const ids = ['A1', 'A2', 'A3', 'A4', 'A5', 'A6'];
const rgb = Float64Array.from([0.1, 0.2, 0.3, 0.5, 0.4, 0.2, 0.2, 0.6, 0.1, 0.3, 0.3, 0.7, 0.8, 0.7, 0.6, 0.4, 0.1, 0.5]);
const xyz = Float64Array.from([10, 12, 20, 30, 28, 12, 20, 35, 8, 25, 22, 50, 60, 62, 55, 20, 10, 30]);
// The test set: the last patch has Y = 0, so its relative Y error is not a number.
const test_xyz = Float64Array.from([...xyz.slice(0, 15), 2, 0, 3]);
const SUMMARY = ['min', 'median', 'mean', 'p95', 'max', 'rms', 'std'];

test('metrics: the module gives the object tristim evaluate prints, null where a figure is not a number', async () => {
  const T = await loadTristim();
  const r = T.fitTables({ characterisation: { model: 'matrix-3x3', objective: { method: 'ls' } } }, ids, rgb, xyz);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-metrics-'));
  try {
    fs.writeFileSync(path.join(dir, 'p.json'), r.profile);
    fs.writeFileSync(path.join(dir, 'rgb.csv'), table('patch,R,G,B', ids, rgb));
    fs.writeFileSync(path.join(dir, 'xyz.csv'), table('patch,X,Y,Z', ids, test_xyz));
    const cli = JSON.parse(execFileSync(CLI, ['evaluate', '--profile', path.join(dir, 'p.json'), '--rgb', path.join(dir, 'rgb.csv'),
      '--xyz', path.join(dir, 'xyz.csv')], { encoding: 'utf8' }));
    const m = T.evaluateProfile(r.profile, rgb, test_xyz, ids).metrics;
    assert.deepEqual(cli.metrics.patches.ids, ids);
    delete cli.metrics.patches.ids;
    assert.deepEqual(m, cli.metrics);
    assert.deepEqual(Object.keys(m), ['dE76', 'dE94', 'dE00', 'dE_xyz', 'abs_rel_Y', 'NRMSE', 'patches']);
    assert.deepEqual(Object.keys(m.patches), ['dE76', 'dE94', 'dE00', 'dL', 'dC', 'dH', 'dE_xyz', 'rel_Y']);
    assert.deepEqual(Object.keys(m.dE00), SUMMARY);
    assert.equal(m.patches.rel_Y[5], null);
    assert.ok(m.patches.rel_Y.slice(0, 5).every(Number.isFinite));
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});

test('metrics: a fit\'s training and leave-one-out metrics, and the comparison rows\' summaries, by the same lists', async () => {
  const T = await loadTristim();
  const e = T.evaluateModel('matrix-3x3', rgb, xyz, { objective: 'ls' }, -1, true);
  assert.deepEqual(e.training, T.evaluate(e.fit.fitted, xyz, [96.4212, 100, 82.5188]));
  assert.deepEqual(e.loo, T.evaluate(e.loo_XYZ, xyz, [96.4212, 100, 82.5188]));
  const rows = T.compareModels(rgb, xyz, {}, ['matrix-3x3'], ['ls'], -1);
  assert.deepEqual(Object.keys(rows[0].train_dE00), SUMMARY);
  assert.equal(rows[0].train_dE00.mean, e.training.dE00.mean);
  assert.equal(rows[0].loo_dE00.mean, e.loo.dE00.mean);
});

test('profile: crosses as its document (what tristim fit writes), back from that object or its text, strictly', async () => {
  const T = await loadTristim();
  const r = T.fitTables({ characterisation: { model: 'matrix-3x3', objective: { method: 'ls' } } }, ids, rgb, xyz);
  const p = T.profileFromJson(r.profile);
  assert.deepEqual(p, JSON.parse(r.profile));
  assert.equal(T.exportCube(p, 5), T.exportCube(r.profile, 5));
  assert.deepEqual(T.profilePredict(p, rgb), T.profilePredict(r.profile, rgb));
  assert.throws(() => T.exportCube({ ...p, colour: 1 }, 5), (e) => e.code === 'PROFILE_INVALID' && /colour/.test(e.message));
  assert.throws(() => T.exportCube({ ...p, version: 2 }, 5), (e) => e.code === 'PROFILE_VERSION');
  assert.throws(() => T.exportCube({ ...p, colorimetry: { ...p.colorimetry, white: [1, -1, 1] } }, 5), (e) => e.code === 'PROFILE_INVALID');
});

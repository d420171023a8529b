// The compare table's rows cross by their field lists (tristim/evaluation/evaluation.hpp): a row of
// compareModels is the object `tristim compare --json` prints in "rows" (without what only the CLI
// adds: the wall and CPU times it measured itself, loo_stopping, bootstrap), a ridge row that same
// object with "ridge": true and "lambda", a stopping check its four members.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, repoRoot } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const table = (head, ids, m) => [head, ...ids.map((id, i) => [id, m[3 * i], m[3 * i + 1], m[3 * i + 2]].join(','))].join('\n') + '\n';

const ids = ['A1', 'A2', 'A3', 'A4', 'A5', 'A6', 'B1'];
const rgb = Float64Array.from([0.1, 0.2, 0.3, 0.5, 0.4, 0.2, 0.2, 0.6, 0.1, 0.3, 0.3, 0.7, 0.8, 0.7, 0.6, 0.4, 0.1, 0.5, 0.6, 0.3, 0.2]);
const xyz = Float64Array.from([10, 12, 20, 30, 28, 12, 20, 35, 8, 25, 22, 50, 60, 62, 55, 20, 10, 30, 35, 30, 15]);
// 7 patches: rows with leave-one-out (3, 4 terms), one exactly determined without it (7 terms), one refused (10).
const MODELS = ['matrix-3x3', 'matrix-3x4', 'Cheung2004-7', 'Cheung2004-10'];
const ROW = ['model', 'objective', 'n_terms', 'ok', 'error_code', 'status', 'message', 'condition_number', 'seconds', 'cpu_seconds',
  'train_dE00', 'train_dE_xyz', 'has_loo', 'loo_dE00', 'loo_dE_xyz'];
const untimed = (r) => { const { seconds, cpu_seconds, loo_stopping, ...rest } = r; return rest; };

test('compareModels: the rows tristim compare --json prints (names, order, values)', async () => {
  const T = await loadTristim();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-compare-'));
  try {
    fs.writeFileSync(path.join(dir, 'rgb.csv'), table('patch,R,G,B', ids, rgb));
    fs.writeFileSync(path.join(dir, 'xyz.csv'), table('patch,X,Y,Z', ids, xyz));
    const cli = JSON.parse(execFileSync(CLI, ['compare', '--rgb', path.join(dir, 'rgb.csv'), '--xyz', path.join(dir, 'xyz.csv'),
      '--models', MODELS.join(','), '--objectives', 'ls', '--json'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
    const rows = T.compareModels(rgb, xyz, {}, MODELS, ['ls'], -1);
    assert.equal(rows.length, 4);
    for (const r of rows) assert.deepEqual(Object.keys(r), r.has_loo ? ROW : ROW.slice(0, -2));
    assert.deepEqual(rows.map(untimed), cli.rows.map(untimed));
    const refused = rows.find((r) => !r.ok);
    assert.equal(refused.model, 'Cheung2004-10');
    assert.equal(refused.status, 'error');
    assert.equal(refused.error_code, 'TOO_FEW_PATCHES');
    const exact = rows.find((r) => r.model === 'Cheung2004-7');
    assert.equal(exact.has_loo, false);
    assert.equal(exact.status, 'exactly_determined');
    assert.equal(exact.objective, 'ls');
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});

test('recipeRidgeRow and recipeStoppingCheck: a ridge row is a compare row with ridge and lambda; a stopping check its members', async () => {
  const T = await loadTristim();
  const recipe = { characterisation: { model: 'Cheung2004-5', objective: { method: 'de2000' } } };
  const ridge = T.recipeRidgeRow(recipe, ids, rgb, xyz);
  assert.deepEqual(Object.keys(ridge), [...ROW, 'ridge', 'lambda']);
  assert.equal(ridge.model, 'Cheung2004-5');
  assert.equal(ridge.ridge, true);
  assert.ok(ridge.ok && Number.isFinite(ridge.lambda) && ridge.lambda >= 0);
  assert.ok(ridge.loo_dE00.mean >= ridge.train_dE00.mean);
  const fit = T.fitTables(recipe, ids, rgb, xyz).evaluation;
  const stop = T.recipeStoppingCheck(recipe, ids, rgb, xyz, fit.loo.dE00.mean, 1e9);
  assert.deepEqual(Object.keys(stop), ['checked', 'flagged', 'loo_mean', 'perturbed_loo_mean']);
  assert.equal(stop.checked, true);
  assert.equal(stop.loo_mean, fit.loo.dE00.mean);
  assert.ok(Number.isFinite(stop.perturbed_loo_mean));
});

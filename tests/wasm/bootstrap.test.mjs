// The bootstrap in the module (wasm/bind_bootstrap.cpp), stepped in chunks as the page's worker
// runs it: the same numbers, to the bit, as `tristim fit --bootstrap` for the same seed, and the
// profile text it writes (patches alone, and patches with each patch's pixels as the page passes a
// sampled RAW's); refusals with codes.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, repoRoot } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const throwsCode = (f, code) => assert.throws(f, (e) => e.code === code);

/// A CSV's rows as {header: value text} objects.
const rows = (text) => {
  const [head, ...lines] = text.trim().split(/\r?\n/);
  const keys = head.split(',');
  return lines.map((l) => Object.fromEntries(l.split(',').map((v, i) => [keys[i], v])));
};

/// The module's bootstrap, stepped as the page steps it, against `tristim fit --bootstrap` on the
/// example's sampled patches (in `dir`): with `pixels`, the CSV keeps sample's R_std, G_std, B_std
/// and n and the module gets them as the page passes a sampled RAW's ({std, n}); without, means
/// only and null (patches alone). Returns the module's fit of the training set.
async function againstCli(T, dir, sampled, pixels) {
  const columns = pixels ? ['R', 'G', 'B', 'R_std', 'G_std', 'B_std', 'n'] : ['R', 'G', 'B'];
  fs.writeFileSync(path.join(dir, 'rgb.csv'), `patch,${columns.join(',')}\n${sampled.map((r) => [r.patch, ...columns.map((c) => r[c])].join(',')).join('\n')}\n`);
  const cliText = execFileSync(CLI, ['fit', '--rgb', path.join(dir, 'rgb.csv'), '--xyz', path.join(dir, 'ref.csv'), '--model', 'Finlayson2015-2',
    '--bootstrap', '200', '--seed', '7', '--level', '0.9', '--recipe-out', path.join(dir, 'recipe.json'), '--csv', path.join(dir, 'fit.csv')],
  { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
  const cli = JSON.parse(cliText);
  assert.equal(cli.bootstrap.resampling, pixels ? 'patches+pixels' : 'patches');
  // The training set in the CLI's order (its per-patch CSV), values as the files give them.
  const order = rows(fs.readFileSync(path.join(dir, 'fit.csv'), 'utf8')).map((r) => r.patch ?? r.id ?? Object.values(r)[0]);
  const byId = new Map(sampled.map((r) => [r.patch, r]));
  const refOf = new Map(rows(fs.readFileSync(path.join(dir, 'ref.csv'), 'utf8')).map((r) => [r.patch, [r.X, r.Y, r.Z].map(Number)]));
  const of = (keys) => Float64Array.from(order.flatMap((id) => keys.map((k) => Number(byId.get(id)[k]))));
  const rgb = of(['R', 'G', 'B']);
  const xyz = Float64Array.from(order.flatMap((id) => refOf.get(id)));
  const fit = T.fitTables(fs.readFileSync(path.join(dir, 'recipe.json'), 'utf8'), order, rgb, xyz);
  const settings = { method: 'bootstrap', parameters: { resamples: 200, seed: 7, level: 0.9 }, settings: {} };
  const px = pixels ? { std: of(['R_std', 'G_std', 'B_std']), n: of(['n']) } : null;
  const run = T.bootstrapRecipe(fit.recipe, fit.ids, fit.linear_RGB, fit.reference_XYZ, fit.evaluation.loo.patches.dE00, settings, px);
  try {
    assert.equal(run.total(), 200);
    const seen = [];
    while (run.done() < run.total()) seen.push(run.step(50));
    assert.deepEqual(seen, [50, 100, 150, 200]);
    const b = run.result();
    const { train_ci, loo_ci, ...rest } = b;
    assert.deepEqual(rest, cli.bootstrap);   // every interval, the covariance, the ellipses: to the bit
    assert.deepEqual(train_ci, cli.metrics.training.dE00.ci);
    assert.deepEqual(loo_ci, cli.metrics.loo.dE00.ci);
    assert.equal(b.predicted_xy_covariance.length, order.length);
    // k² = ν((1 − level)^(−2/ν) − 1), ν = N − 6 (Finlayson2015-2's terms): F(2, ν) at 0.9, above χ²₂'s √(−2 ln 0.1) = 2.146.
    const nu = order.length - 6;
    assert.ok(Math.abs(b.ellipse_scale - Math.sqrt(nu * (0.1 ** (-2 / nu) - 1))) < 1e-12);
    assert.ok(b.ellipse_scale > 2.15);
    assert.equal(run.profileWith(fit.profile), cliText);
  } finally {
    run.delete();
  }
  return { fit, settings };
}

test('bootstrap: chunked in the module = tristim fit --bootstrap (same seed, patches alone and with pixels), profile text too', async () => {
  const T = await loadTristim();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-bootstrap-'));
  try {
    const dng = path.join(repoRoot, 'examples/web/passport.dng');
    const sampled = rows(execFileSync(CLI, ['sample', dng, '--chart', 'passport', '--corners', '335,291,649,285,649,486,328,488'], { encoding: 'utf8' }));
    fs.writeFileSync(path.join(dir, 'ref.csv'), execFileSync(CLI, ['reference', '--chart', 'passport', '--illuminant', 'D50']));
    await againstCli(T, dir, sampled, true);
    const { fit, settings } = await againstCli(T, dir, sampled, false);
    // Table-driven settings (the page's form): ranges and defaults from the engine.
    const info = T.bootstrapOptions();
    assert.deepEqual(info.options.map((o) => o.name), ['resamples', 'seed', 'level']);
    assert.equal(info.options[0].default_number, 1000);
    const bad = (parameters) => () => T.bootstrapRecipe(fit.recipe, fit.ids, fit.linear_RGB, fit.reference_XYZ, null, { method: 'bootstrap', parameters, settings: {} }, null);
    throwsCode(bad({ resamples: 0 }), 'INVALID_ARGUMENT');
    throwsCode(bad({ level: 1 }), 'INVALID_ARGUMENT');
    throwsCode(bad({ samples: 10 }), 'UNKNOWN_ID');
    throwsCode(() => T.bootstrapRecipe(fit.recipe, fit.ids.slice(1), fit.linear_RGB, fit.reference_XYZ, null, settings, null), 'INVALID_ARGUMENT');
    throwsCode(() => T.bootstrapRecipe(fit.recipe, fit.ids, fit.linear_RGB, fit.reference_XYZ, null, settings,
      { std: new Float64Array(3), n: new Float64Array(1) }), 'INVALID_ARGUMENT');   // pixel statistics of one patch for 24
    // A cancelled run (fewer resamples than asked) says so.
    const part = T.bootstrapRecipe(fit.recipe, fit.ids, fit.linear_RGB, fit.reference_XYZ, null, settings, null);
    part.step(30);
    const r = part.result();
    part.delete();
    assert.equal(r.cancelled, true);
    assert.equal(r.resamples, 30);
    assert.equal(r.loo_ci, undefined);
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});

// Linearisation, CurveSamples, SpectralModel and SpectralEvaluation cross by their field lists
// (tristim/linearisation/linearisation.hpp, spectral.hpp): each object is what the CLI prints —
// `tristim linearise --json` (its "linearisation" and "curves"), `tristim spectral fit --out` (the
// model document), `tristim spectral apply --json` (the errors) — and comes back through the
// same strict reader (an unknown member refused). Native and wasm agree to ~1e-12 here (Shen2008's
// SVD rounds differently), so numbers are compared to a stated tolerance; names, order, strings,
// nulls and lengths exactly.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, repoRoot, throwsCode } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const GREYS = 'D1;D2;D3;D4;D5;D6';

// The ColorChecker through the virtual camera as in Shen et al. 2008 eq (29): 8-bit, γ = 1.8, l = 22.
async function simulated() {
  const T = await loadTristim();
  const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D65',
    { white_level: 80, oecf: true, oecf_gamma: 1.8, oecf_scale: 22, clip_max: 255, quantise: true });
  const rgb = Float64Array.from(sim.RGB), ids = Array.from(sim.ids);
  const csv = ['patch,R,G,B', ...ids.map((id, i) => [id, rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]].join(','))].join('\n') + '\n';
  return { T, rgb, ids, csv, cc24: T.chartReflectances('cc24') };
}

/// a and b have the same members in the same order, the same strings, booleans, nulls and lengths,
/// and numbers within 1e-9 relative (the worst element named).
function sameShape(a, b, where = '') {
  if (typeof a === 'number' && typeof b === 'number') {
    assert.ok(Math.abs(a - b) <= 1e-9 * Math.max(1, Math.abs(a)), `${where}: module ${a}, CLI ${b} (tolerance 1e-9 relative)`);
  } else if (Array.isArray(a) && Array.isArray(b)) {
    assert.equal(a.length, b.length, `${where}: length`);
    a.forEach((x, i) => sameShape(x, b[i], `${where}[${i}]`));
  } else if (a && b && typeof a === 'object' && typeof b === 'object') {
    assert.deepEqual(Object.keys(a), Object.keys(b), `${where}: members`);
    for (const k of Object.keys(a)) sameShape(a[k], b[k], where ? `${where}.${k}` : k);
  } else {
    assert.equal(a, b, where);
  }
}

const cli = (args) => execFileSync(CLI, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });

test('linearisation fields: the module\'s objects are the CLI\'s JSON', async () => {
  const { T, rgb, ids, csv, cc24 } = await simulated();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-linfields-'));
  try {
    const rgbFile = path.join(dir, 'rgb.csv'), linFile = path.join(dir, 'lin.json'), model = path.join(dir, 'model.json');
    fs.writeFileSync(rgbFile, csv);
    const out = cli(['linearise', '--method', 'Shen2008', '--rgb', rgbFile, '--reflectances', 'cc24', '--grey', GREYS, '--full-scale', '255', '--json']);
    fs.writeFileSync(linFile, out);
    const printed = JSON.parse(out);
    const lin = T.fitLinearisation({ method: 'Shen2008', settings: { grey: GREYS } }, { camera_RGB: rgb, ids, reflectances: cc24, full_scale: 255 });
    sameShape(lin, printed.linearisation);
    assert.deepEqual(Object.keys(lin).slice(0, 4), ['method', 'parameters', 'settings', 'full_scale']);
    assert.ok(lin.extrapolated.length > 0, 'Shen2008 on the non-grey patches extrapolates to the white');
    for (let c = 0; c < 3; c++) sameShape({ channel: 'RGB'[c], ...T.sampleCurve(lin, c, 101) }, printed.curves[c], `curves[${c}]`);
    // a curve without a grey-based one has no grey_based member, as in the CLI's curves
    const gamma = T.fitLinearisation('gamma:gamma=1.8', { camera_RGB: rgb, ids, full_scale: 255 });
    assert.deepEqual(Object.keys(T.sampleCurve(gamma, 0, 5)), ['x', 'linear']);
    assert.equal(gamma.r_squared[0], null);

    // spectral fit: the model document (without the training errors the CLI writes beside it)
    cli(['spectral', 'fit', '--rgb', rgbFile, '--reflectances', 'cc24', '--linearisation', linFile, '--out', model]);
    const doc = JSON.parse(fs.readFileSync(model, 'utf8'));
    const m = T.fitSpectral(lin, ids, rgb, cc24);
    sameShape(T.evaluateSpectral(m, ids, rgb, cc24, 'D65', '1931'), doc.training, 'training');
    delete doc.training;
    sameShape(m, doc);
    assert.equal(m.W.length, m.wavelengths.length);
    assert.deepEqual(JSON.parse(T.spectralModelToJson(m)), m);
    // spectral apply --json: the errors
    const applied = JSON.parse(cli(['spectral', 'apply', model, '--rgb', rgbFile, '--reflectances', 'cc24', '--json']));
    const e = T.evaluateSpectral(doc, ids, rgb, cc24, 'D65', '1931');
    sameShape(e, applied);
    assert.deepEqual(Object.keys(e.summary), ['spectral_rms_mean', 'spectral_rms_std', 'spectral_rms_max', 'dE00_mean', 'dE00_std', 'dE00_max']);
    assert.deepEqual(e.patches.map((p) => p.patch), ids);
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});

test('linearisation fields: objects and texts round-trip; unknown members and broken curves refused', async () => {
  const { T, rgb, ids, cc24 } = await simulated();
  const lin = T.fitLinearisation('Shen2008', { camera_RGB: rgb, ids, reflectances: cc24, full_scale: 255 });
  const text = T.linearisationToJson(lin);
  assert.deepEqual(JSON.parse(text), lin);
  assert.deepEqual(T.linearisationFromJson(text), lin);
  assert.deepEqual(Array.from(T.linearise(JSON.parse(text), rgb)), Array.from(T.linearise(lin, rgb)));
  throwsCode(assert, () => T.linearise({ ...lin, spline: 1 }, rgb), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.linearise({ ...lin, coefficients: [[], [], []] }, rgb), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.linearise({ ...lin, method: 'spline' }, rgb), 'UNKNOWN_ID');
  throwsCode(assert, () => T.linearisationFromJson(JSON.stringify({ ...lin, spline: 1 })), 'PROFILE_INVALID');
  const m = T.fitSpectral(lin, ids, rgb, cc24);
  throwsCode(assert, () => T.estimateReflectances({ ...m, extra: [] }, ids, rgb), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.estimateReflectances({ ...m, W: m.W.slice(1) }, ids, rgb), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.estimateReflectances({ ...m, format: 'tristim-profile' }, ids, rgb), 'INVALID_ARGUMENT');
});

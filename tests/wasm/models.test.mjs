import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, readBytes, readText, testFiles, throwsCode } from './load.mjs';

// The Passport patches (camera RGB derived from the DNG) and X-Rite's CC24 reference (Lab D50).
function csvRows(file) {
  const text = readText(file);
  const [head, ...lines] = text.trim().split('\n');
  const cols = head.split(',');
  return lines.map((l) => Object.fromEntries(l.split(',').map((v, i) => [cols[i], v])));
}
function labToXYZ([L, a, b], w = [96.4212, 100, 82.5188]) {
  const fy = (L + 16) / 116, fx = fy + a / 500, fz = fy - b / 200;
  const inv = (t) => (t > 6 / 29 ? t ** 3 : 3 * (6 / 29) ** 2 * (t - 4 / 29));
  return [w[0] * inv(fx), w[1] * inv(fy), w[2] * inv(fz)];
}
function passport() {
  const rgbRows = csvRows(testFiles.passportRgbCsv);
  const refRows = csvRows('core/data/charts/colorchecker24_xrite_before_nov2014_Lab_D50.csv');
  const rgb = new Float64Array(72), xyz = new Float64Array(72);
  const ids = [];
  rgbRows.forEach((r, i) => {
    rgb.set([+r.R, +r.G, +r.B], 3 * i);
    const ref = refRows.find((q) => q.patch === r.patch);
    xyz.set(labToXYZ([+ref.L, +ref.a, +ref.b]), 3 * i);
    ids.push('ABCD'[Math.floor(i / 6)] + ((i % 6) + 1));
  });
  return { rgb, xyz, ids };
}

/// A fit from a recipe's characterisation and evaluation stages, on paired tables.
const fitModel = (T, rgb, xyz, ids, characterisation, evaluation = {}) => T.fitTables({ characterisation, evaluation }, ids, rgb, xyz);
const numbered = (n) => Array.from({ length: n }, (_, i) => String(i + 1));

test('listModels / listObjectives describe the method table', async () => {
  const T = await loadTristim();
  const models = T.listModels();
  const ids = models.map((m) => m.id);
  for (const id of ['matrix-3x3', 'matrix-3x4', 'Shen2008', 'Finlayson2015-2', 'Cheung2004-35', 'Guarnera2018-T2R'])
    assert.ok(ids.includes(id), id);
  const t2r = models.find((m) => m.id === 'Guarnera2018-T2R');
  assert.equal(t2r.n_terms, 6);
  assert.equal(t2r.duplicate_of, 'Finlayson2015-2');
  assert.deepEqual(T.listObjectives().map((o) => o.id), ['ls', 'psm', 'de2000']);
  // Every model names its family; the families come in the order of their first model.
  const families = T.listModelFamilies();
  assert.deepEqual(families.map((f) => f.id), [...new Set(models.map((m) => m.family))]);
  assert.equal(t2r.family, 'Guarnera2018');
  assert.ok(families.every((f) => f.label && f.about), 'each family has a label and its advice');
});

test('fitModel: planted 3x3 recovered, profile round-trips through evaluateProfile', async () => {
  const T = await loadTristim();
  const M = [40, 30, 15, 20, 70, 8, 2, 10, 90];
  const n = 20, rgb = new Float64Array(3 * n), xyz = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) {
    const c = [0.1 + ((i * 37) % 17) / 20, 0.1 + ((i * 11) % 13) / 15, 0.1 + ((i * 7) % 19) / 22];
    rgb.set(c, 3 * i);
    for (let k = 0; k < 3; k++) xyz[3 * i + k] = M[3 * k] * c[0] + M[3 * k + 1] * c[1] + M[3 * k + 2] * c[2];
  }
  for (const objective of ['ls', 'psm', 'de2000']) {
    const r = fitModel(T, rgb, xyz, numbered(n), { model: 'matrix-3x3', objective: { method: objective } });
    const coefficients = r.evaluation.fit.model.coefficients;
    assert.ok(coefficients instanceof Float64Array);
    coefficients.forEach((v, i) => assert.ok(Math.abs(v - M[i]) < 1e-9, `${objective} coef ${i}: ${v}`));
    assert.ok(r.evaluation.training.dE00.max < 1e-6);
    assert.ok(r.evaluation.loo.dE00.max < 1e-6);
    const p = JSON.parse(r.profile);
    assert.equal(p.format, 'tristim-profile');
    assert.equal(p.version, 1);
    const ev = T.evaluateProfile(r.profile, rgb, xyz, []);
    assert.equal(ev.same_data_as_training, true);
    assert.ok(ev.estimated instanceof Float64Array);
    ev.estimated.forEach((v, i) => assert.equal(v, r.evaluation.fit.fitted[i]));
  }
});

test('fitModel on the Passport patches: LOO reported, best model beats the 3x3', async () => {
  const T = await loadTristim();
  const { rgb, xyz, ids } = passport();
  const a = fitModel(T, rgb, xyz, ids, { model: 'matrix-3x3', objective: { method: 'ls' } }).evaluation;
  const b = fitModel(T, rgb, xyz, ids, { model: 'Finlayson2015-2', objective: { method: 'ls' } }).evaluation;
  assert.equal(a.fit.status, 'ok');
  assert.equal(a.training.patches.dE00.length, 24);
  assert.equal(a.loo.patches.dE00.length, 24);
  assert.ok(b.loo.dE00.mean < a.loo.dE00.mean);
  assert.ok(a.fit.condition_number > 1 && a.fit.condition_number < 1e3);
  const w = fitModel(T, rgb, xyz, ids, { model: 'matrix-3x4', objective: { method: 'de2000' }, white_patch: 'D1' }).evaluation;
  const est = w.fit.fitted.slice(18 * 3, 18 * 3 + 3);
  for (let k = 0; k < 3; k++) assert.ok(Math.abs(est[k] - xyz[18 * 3 + k]) < 1e-9);
});

test('compareModels: rows sorted by held-out error, refusals last with a code', async () => {
  const T = await loadTristim();
  const { rgb, xyz, ids } = passport();
  const rows = T.compareModels(rgb, xyz, {}, [], ['ls'], -1);
  assert.ok(rows.length > 10);
  const okRows = rows.filter((r) => r.ok && r.has_loo);
  for (let i = 1; i < okRows.length; i++) assert.ok(okRows[i].loo_dE00.mean >= okRows[i - 1].loo_dE00.mean);
  const last = rows[rows.length - 1];
  assert.equal(last.ok, false);
  assert.equal(last.error_code, 'TOO_FEW_PATCHES');
});

test('applyProfileToImage, exportIcc, exportCube, patchCsv', async () => {
  const T = await loadTristim();
  const { rgb, xyz, ids } = passport();
  const r = fitModel(T, rgb, xyz, ids, { model: 'Finlayson2015-2' });
  const w = 4, h = 6;
  const img = new Float32Array(w * h * 3);
  for (let i = 0; i < 24; i++) img.set(rgb.subarray(3 * i, 3 * i + 3), 3 * i);
  const out = T.applyProfileToImage(r.profile, img, w, h).pixels;
  const fitted = r.evaluation.fit.fitted;
  assert.ok(out instanceof Float32Array);
  assert.equal(out.length, w * h * 3);
  for (let i = 0; i < 72; i++) assert.ok(Math.abs(out[i] - fitted[i]) < 1e-3 * (1 + Math.abs(fitted[i])));
  const icc = T.exportIcc(r.profile);
  assert.ok(icc instanceof Uint8Array);
  assert.equal(String.fromCharCode(...icc.slice(36, 40)), 'acsp');
  assert.equal(icc[8], 4);
  const icc2 = T.exportIcc(r.profile, { version: 2.4, grid_points: 17 });
  assert.equal(icc2[8], 2);
  const cube = T.exportCube(r.profile, 9);
  assert.match(cube, /LUT_3D_SIZE 9/);
  // Resolve convention: a 1D shaper of LUT_1D_SIZE rows, then the 9³ rows of the 3D LUT.
  const shaper = Number(cube.match(/^LUT_1D_SIZE (\d+)$/m)[1]);
  assert.ok(shaper >= 2);
  assert.equal(cube.trim().split('\n').filter((l) => /^[-0-9]/.test(l)).length, shaper + 9 ** 3);
  const csv = T.patchCsv(ids, rgb, xyz, fitted, [96.4212, 100, 82.5188], r.evaluation.loo_XYZ);
  assert.equal(csv.trim().split('\n').length, 25);
});

test('bad input reaches JS as coded errors', async () => {
  const T = await loadTristim();
  const { rgb, xyz, ids } = passport();
  throwsCode(assert, () => fitModel(T, rgb, xyz.subarray(0, 69), ids, { model: 'matrix-3x3' }), 'PATCH_MISMATCH');
  throwsCode(assert, () => fitModel(T, rgb, xyz, ids.slice(1), { model: 'matrix-3x3' }), 'PATCH_MISMATCH');
  throwsCode(assert, () => fitModel(T, rgb, xyz, ids, { model: 'nope' }), 'UNKNOWN_ID');
  throwsCode(assert, () => fitModel(T, rgb, xyz, ids, { model: 'Cheung2004-35' }), 'TOO_FEW_PATCHES');
  const nan = rgb.slice();
  nan[4] = NaN;
  throwsCode(assert, () => fitModel(T, nan, xyz, ids, { model: 'matrix-3x3' }), 'NON_FINITE');
  const neg = xyz.slice();
  neg[5] = -1;
  throwsCode(assert, () => fitModel(T, rgb, neg, ids, { model: 'matrix-3x3' }), 'NEGATIVE_VALUE');
  throwsCode(assert, () => fitModel(T, rgb, xyz, ids, { model: 'matrix-3x3', objective: { method: 'magic' } }), 'UNKNOWN_ID');
  const good = fitModel(T, rgb, xyz, ids, { model: 'matrix-3x3' }, { leave_one_out: false }).profile;
  throwsCode(assert, () => T.evaluateProfile(good.replace('"version": 1', '"version": 7'), rgb, xyz, ids), 'PROFILE_VERSION');
  throwsCode(assert, () => T.evaluateProfile('{"format": "tristim-profile", "version": 1}', rgb, xyz, ids), 'PROFILE_INVALID');
  throwsCode(assert, () => T.exportIcc('not json'), 'PROFILE_INVALID');
  throwsCode(assert, () => T.applyProfileToImage(good, new Float32Array(10), 2, 2), 'ROW_LENGTH');
});

test('applyProfile on a decoded RAW gives an XYZ image of the RAW size', async () => {
  const T = await loadTristim();
  const { rgb, xyz, ids } = passport();
  const r = fitModel(T, rgb, xyz, ids, { model: 'matrix-3x3' }, { leave_one_out: false });
  const raw = T.decodeRaw(readBytes(testFiles.passportDng));
  try {
    const out = T.applyProfile(r.profile, raw);
    assert.equal(out.width, raw.width());
    assert.equal(out.height, raw.height());
    assert.ok(out.pixels instanceof Float32Array);
    assert.equal(out.pixels.length, raw.width() * raw.height() * 3);
    const lin = raw.linearRGB();
    const M = r.evaluation.fit.model.coefficients;
    const i = 3 * (Math.floor(raw.height() / 2) * raw.width() + Math.floor(raw.width() / 2));
    for (let k = 0; k < 3; k++) {
      const want = M[3 * k] * lin[i] + M[3 * k + 1] * lin[i + 1] + M[3 * k + 2] * lin[i + 2];
      assert.ok(Math.abs(out.pixels[i + k] - want) < 1e-4 * (1 + Math.abs(want)));
    }
  } finally {
    raw.delete();
  }
  throwsCode(assert, () => T.applyProfile(r.profile, {}), 'INVALID_ARGUMENT');
});

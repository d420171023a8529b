// The colorimetry lab through the wasm module (issue 45): a rendered chart DNG decoded, detected
// and sampled back to its truth to 1e-6, byte-identical to the native CLI's file (and the same
// truth text); camera quality (SMI, μ) as the CLI prints it, the ranking of the 52, the best-fit
// CMF combination; coded errors for bad options.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, throwsCode, repoRoot } from './load.mjs';

const nativeCli = path.join(repoRoot, 'build/native/core/tristim');
const OPTIONS = { camera: 'Nikon_D850', chart: 'passport', illuminant: 'D50', exposure: 0.6, flare: 0.01 };

function render(T, options) {
  return T.labRender({ ...options, illuminant_spd: T.illuminantSpectrum(options.illuminant) });
}

test('lab render: the DNG decodes, is detected and sampled back to the truth (noise off, 1e-6)', async () => {
  const T = await loadTristim();
  const out = render(T, OPTIONS);
  const truth = JSON.parse(out.truth);
  const raw = T.decodeRaw(out.dng);
  try {
    const found = T.detectCharts(raw, { charts: ['passport'] });
    assert.equal(found[0].chart, 'passport');
    const s = T.sampleChart(raw, { chart: 'passport' }, found[0].corners);
    let worst = { e: 0 };
    s.patches.forEach((p, k) => {
      assert.equal(p.id, truth.patches[k].id);
      [0, 1, 2].forEach((c) => {
        const e = Math.abs(p.mean[c] - truth.patches[k].rgb[c]);
        if (e > worst.e) worst = { e, at: `${p.id} ${'RGB'[c]}: sampled ${p.mean[c]}, truth ${truth.patches[k].rgb[c]}` };
      });
    });
    assert.ok(worst.e <= 1e-6, worst.at);
  } finally { raw.delete(); }
});

test('lab render: the page\'s DNG and truth are the native CLI\'s, byte for byte (noise on)', async () => {
  assert.ok(fs.existsSync(nativeCli), `${nativeCli} not found: scripts/build.sh builds it`);
  const T = await loadTristim();
  const options = { ...OPTIONS, shot_gain: 2, read_noise: 4, seed: 9, falloff: 0.2 };
  const out = render(T, options);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-lab-'));
  try {
    const file = path.join(dir, 'chart.dng');
    const text = execFileSync(nativeCli, ['lab', 'render', '--camera', options.camera, '--chart', options.chart, '--illuminant', options.illuminant,
      '--exposure', '0.6', '--flare', '0.01', '--noise', '2,4', '--seed', '9', '--falloff', '0.2', '--out', file]).toString();
    const native = fs.readFileSync(file);
    assert.equal(native.length, out.dng.length);
    assert.ok(Buffer.from(out.dng).equals(native), 'the DNG bytes differ between the CLI and wasm');
    assert.equal(text.trim(), out.truth.trim());
  } finally { fs.rmSync(dir, { recursive: true, force: true }); }
});

test('lab smi: the ranking of the 52 cameras, and one camera as the CLI prints it', async () => {
  const T = await loadTristim();
  const D65 = T.illuminantSpectrum('D65');
  const rows = T.cameraQualityRanking(D65);
  assert.equal(rows.length, T.listCameras().length);
  rows.forEach((r, i) => {
    if (i > 0) assert.ok(r.smi <= rows[i - 1].smi, `${r.camera} after ${rows[i - 1].camera}`);
    assert.ok(r.mu_factor > 0.8 && r.mu_factor < 1, `${r.camera} mu ${r.mu_factor}`);
  });
  const name = 'Canon_EOS_5D_Mark_II';
  const q = T.cameraQuality(T.cameraSensitivities(name), D65, name);
  const native = JSON.parse(execFileSync(nativeCli, ['lab', 'smi', '--camera', name, '--json']).toString())[0];
  assert.equal(native.camera, name);
  assert.ok(Math.abs(q.smi - native.smi) < 1e-9, `wasm ${q.smi} native ${native.smi}`);
  assert.ok(Math.abs(q.mu_factor - native.mu_factor) < 1e-12, `wasm ${q.mu_factor} native ${native.mu_factor}`);
  assert.equal(q.matrix.length, 9);
  assert.equal(q.dE.length, 18);
  assert.ok(Math.abs(q.dE.reduce((a, b) => a + b) / 18 - q.mean_dE) < 1e-12, 'mean_dE is the mean of dE');
  const fit = T.lutherFit(T.cameraSensitivities(name), D65);
  assert.equal(fit.camera.length, 3);
  assert.equal(fit.fit[1].length, fit.wavelengths.length);
  assert.equal(Math.max(...fit.camera.map((v) => Math.max(...v))), 1);
});

test('lab: bad options give coded errors', async () => {
  const T = await loadTristim();
  throwsCode(assert, () => render(T, { ...OPTIONS, chart: 'it8' }), 'UNKNOWN_ID');
  throwsCode(assert, () => render(T, { ...OPTIONS, camera: 'Kodak Brownie' }), 'UNKNOWN_ID');
  throwsCode(assert, () => render(T, { ...OPTIONS, exposure: -1 }), 'INVALID_ARGUMENT');
  throwsCode(assert, () => render(T, { ...OPTIONS, colour: 'red' }), 'INVALID_ARGUMENT');
});

test('lab exercises: spectra to colour and the over-fitting table, as the CLI prints them', async () => {
  const T = await loadTristim();
  const e = T.labSpectraToColour('cc24', 'C3', ['D65', 'A'], ['1931']);
  assert.equal(e.rows.length, 2);
  const ref = T.referenceChart('cc24', 'A', '1931');
  const k = Array.from(ref.ids).indexOf('C3');
  assert.deepEqual(Array.from(e.rows[1].XYZ), Array.from(ref.XYZ.slice(3 * k, 3 * k + 3)));
  const rows = T.labOverfit(T.cameraSensitivities('Canon_EOS_5D_Mark_II'), T.illuminantSpectrum('D65'), {});
  const native = JSON.parse(execFileSync(nativeCli, ['lab', 'overfit', '--json']).toString());
  assert.equal(rows.length, native.length);
  rows.forEach((r, i) => {
    assert.equal(r.model, native[i].model);
    assert.equal(r.error_code, native[i].error_code);
    if (r.ok) for (const f of ['train_dE00', 'test_dE00']) assert.ok(Math.abs(r[f] - native[i][f]) < 1e-9, `${r.model} ${r.training} ${f}: ${r[f]} vs ${native[i][f]}`);
    // a figure that is not a number is null in both (the JSON's form), never NaN
    for (const f of ['train_dE00', 'loo_dE00', 'test_dE00']) assert.equal(r[f] === null, native[i][f] === null, `${r.model} ${r.training} ${f}`);
    if (!r.ok) assert.ok(r.message.length > 0 && r.train_dE00 === null, `${r.model} ${r.training}: refused with a message`);
  });
  assert.ok(rows.some((r) => !r.ok), 'a refused row (35 terms on 24 patches)');
});

test('lab metamers: the search and a constructed metamer as the CLI prints them; coded errors', async () => {
  const T = await loadTristim();
  const cli = (...a) => JSON.parse(execFileSync(nativeCli, ['lab', 'metamers', ...a, '--json']).toString());
  const found = T.labMetamers({ illuminant: 'D65', second: 'A', max_match: 0.5, top: 3 });
  const nf = cli('--illuminant', 'D65', '--second', 'A', '--max-match', '0.5', '--top', '3');
  assert.equal(found.matching, nf.matching);
  assert.equal(found.compared, nf.compared);
  assert.deepEqual(found.pairs.map((p) => [p.a, p.b]), nf.pairs.map((p) => [p.a, p.b]));
  const made = T.labConstructMetamer({ camera: 'Nikon_D850', second: 'F11' }, '5R5/6');
  const nm = cli('--camera', 'Nikon_D850', '--second', 'F11', '--construct', '5R5/6');
  const [p, q] = [made.pairs[0], nm.pairs[0]];
  let worst = { e: 0 };
  p.reflectance_b.forEach((v, i) => { const e = Math.abs(v - q.reflectance_b[i]); if (e > worst.e) worst = { e, at: `${i}: ${v} vs ${q.reflectance_b[i]}` }; });
  assert.ok(worst.e < 1e-9, `metamer reflectance, worst ${worst.at}`);
  p.views.forEach((v, k) => {
    assert.equal(v.viewer, q.views[k].viewer);
    for (const f of ['dE00_1', 'dE00_2']) assert.ok(Math.abs(v[f] - q.views[k][f]) < 1e-9, `${v.viewer} ${f}: ${v[f]} vs ${q.views[k][f]}`);
  });
  assert.ok(p.views[0].dE00_1 < 1e-9 && p.views[0].dE00_2 > 1);
  assert.equal(T.listMunsell().length, 1269);
  throwsCode(assert, () => T.labConstructMetamer({}, '99Q1/1'), 'UNKNOWN_ID');
  throwsCode(assert, () => T.labMetamers({ match: 'camera' }), 'INVALID_ARGUMENT');
});

test('lab render: the JPEG (sRGB OECF, quality 95) is byte-identical to the CLI\'s, and its truth states the quality', async () => {
  const T = await loadTristim();
  const out = T.labRender({ ...OPTIONS, oecf: 'sRGB', illuminant_spd: T.illuminantSpectrum(OPTIONS.illuminant) }, 'jpeg');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'lab-jpeg-'));
  try {
    const file = path.join(dir, 'chart.jpg');
    const truth = JSON.parse(execFileSync(nativeCli, ['lab', 'render', '--camera', OPTIONS.camera, '--chart', OPTIONS.chart,
      '--illuminant', OPTIONS.illuminant, '--exposure', String(OPTIONS.exposure), '--flare', String(OPTIONS.flare), '--oecf', 'sRGB',
      '--out', file]).toString());
    assert.equal(Buffer.compare(Buffer.from(out.dng), fs.readFileSync(file)), 0);
    assert.deepEqual(JSON.parse(out.truth), truth);
    assert.equal(truth.jpeg_quality, 95);
  } finally { fs.rmSync(dir, { recursive: true, force: true }); }
  throwsCode(assert, () => T.labRender({ ...OPTIONS, oecf: 'sRGB', jpeg_quality: 0, illuminant_spd: T.illuminantSpectrum('D50') }, 'jpeg'), 'INVALID_ARGUMENT');
});

import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, readText, testFiles, throwsCode, repoRoot } from './load.mjs';
import { assertPatchArrays } from './patch_arrays.mjs';

const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (tolerance ${tol})`);

test('catalogue: charts, illuminants, cameras', async () => {
  const T = await loadTristim();
  const charts = T.listCharts();
  assert.deepEqual(charts.map((c) => c.id), ['cc24', 'cc24-2005', 'sg140', 'sg140-2005', 'passport']);
  assert.equal(charts.find((c) => c.id === 'sg140').patches, 140);
  const ill = T.listIlluminants().map((i) => i.id);
  for (const id of ['A', 'D50', 'D55', 'D65', 'D75', 'E', 'F2', 'F11']) assert.ok(ill.includes(id), id);
  const cams = T.listCameras();
  assert.equal(cams.length, 52);
  assert.ok(cams.some((c) => c.id === 'Canon_EOS_5D_Mark_II' && c.name === 'Canon EOS 5D Mark II'));
});

test('referenceChart: shapes and values', async () => {
  const T = await loadTristim();
  const r = T.referenceChart('cc24', 'D65', '1931');
  assertPatchArrays(r, { count: 24, first: 'A1', last: 'D6' }, ['XYZ', 'Lab', 'sRGB']);
  assert.equal(r.white.length, 3);
  close(r.white[1], 100, 1e-9, 'white Y');
  // Native `tristim reference --chart cc24` (D65, 1931), printed to 6 decimals.
  const nativeA1 = [10.807538, 9.666961, 6.299969, 37.237949, 12.758727, 14.434340];
  for (let k = 0; k < 3; k++) close(r.XYZ[k], nativeA1[k], 5e-7, `XYZ[${k}]`);
  for (let k = 0; k < 3; k++) close(r.Lab[k], nativeA1[3 + k], 5e-7, `Lab[${k}]`);
  for (const v of r.sRGB) assert.ok(v >= 0 && v <= 1);
  // SG, 10° observer, a D-series illuminant from its CCT.
  const sg = T.referenceChart('sg140', 'D4500', '1964');
  assert.equal(sg.ids.length, 140);
  assert.equal(sg.ids[139], 'N10');
  assert.equal(T.referenceChart('cc24', 'D50', 1931).ids.length, 24);
});

// Native and wasm: the same core, the same IEEE doubles; only libm differs (glibc natively, musl
// in Emscripten), whose pow/cbrt/log/sin may differ in the last bit. The CLI prints 17 significant
// digits (round-trip exact). Sums and products (XYZ, linear camera RGB) must be bit-identical, and
// so must Lab (its cube roots are core/src/detmath.hpp's, not the C library's) and the virtual
// camera's noise (Box-Muller through detmath's log, sin, cos).
test('referenceChart and simulateCamera agree with the native CLI (when the native build exists)', async (t) => {
  const exe = path.join(repoRoot, 'build/native/core/tristim');
  assert.ok(fs.existsSync(exe), `${exe} not found: scripts/build.sh builds it`);
  const T = await loadTristim();
  const worst = {};
  const compare = (kind, got, want, what) => {
    const d = Math.abs(got - want) / Math.max(1, Math.abs(want));
    if (!worst[kind] || d > worst[kind].d) worst[kind] = { d, what: `${what}: wasm ${got} native ${want}` };
  };
  for (const [chart, ill, obs] of [['cc24', 'D50', '1931'], ['sg140-2005', 'F11', '1964'], ['passport', 'A', '1931'], ['sg140', 'D65', '1931']]) {
    const csv = execFileSync(exe, ['reference', '--chart', chart, '--illuminant', ill, '--observer', obs, '--precision', '17']).toString();
    const rows = csv.trim().split('\n').slice(1).map((l) => l.split(','));
    const r = T.referenceChart(chart, ill, obs);
    assert.equal(rows.length, r.ids.length);
    rows.forEach((row, i) => {
      assert.equal(row[0], r.ids[i]);
      for (let k = 0; k < 3; k++) compare('XYZ', r.XYZ[3 * i + k], Number(row[1 + k]), `${chart} ${row[0]} XYZ[${k}]`);
      for (let k = 0; k < 3; k++) compare('Lab', r.Lab[3 * i + k], Number(row[4 + k]), `${chart} ${row[0]} Lab[${k}]`);
    });
  }
  for (const noise of [0, 0.01]) {
    const kind = noise ? 'RGB+noise' : 'RGB';
    const csv = execFileSync(exe, ['simulate', '--camera', 'Canon_EOS_5D_Mark_II', '--reflectances', 'sg140', '--illuminant', 'D65',
      '--noise', String(noise), '--seed', '9', '--precision', '17']).toString();
    const rows = csv.trim().split('\n').slice(1).map((l) => l.split(','));
    const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'sg140', 'D65', { noise_sigma: noise, seed: 9 });
    rows.forEach((row, i) => { for (let k = 0; k < 3; k++) compare(kind, sim.RGB[3 * i + k], Number(row[1 + k]), `simulate ${row[0]}[${k}]`); });
  }
  for (const [kind, w] of Object.entries(worst)) t.diagnostic(`${kind}: worst relative difference ${w.d} (${w.what})`);
  assert.equal(worst.XYZ.d, 0, `XYZ not bit-identical: ${worst.XYZ.what}`);
  assert.equal(worst.RGB.d, 0, `linear RGB not bit-identical: ${worst.RGB.what}`);
  assert.equal(worst.Lab.d, 0, `Lab not bit-identical: ${worst.Lab.what}`);
  assert.equal(worst['RGB+noise'].d, 0, `noise not bit-identical: ${worst['RGB+noise'].what}`);
});

test('parseReferenceFile: spectral CSV, Lab CSV and CGATS', async () => {
  const T = await loadTristim();
  const spectral = readText('core/data/charts/colorchecker24_after_nov2014_reflectance_380-730_10nm.csv');
  const a = T.parseReferenceFile(spectral, 'cc24.csv', 'D65', '1931');
  const b = T.referenceChart('cc24', 'D65', '1931');
  assert.equal(T.parsePatchFile(spectral, 'cc24.csv').format, 'csv-spectral');
  assert.deepEqual(a.ids, b.ids);
  for (let i = 0; i < 72; i++) assert.equal(a.XYZ[i], b.XYZ[i]);  // same spectra, same numbers
  const lab = T.parseReferenceFile('patch,L,a,b\nA01,50,10,-10\nA02,60,0,0\n', 'lab.csv', 'D50', '1931');
  assert.deepEqual(lab.ids, ['A1', 'A2']);
  assert.deepEqual(Array.from(lab.Lab.slice(0, 3)), [50, 10, -10]);
  const cie = T.parseReferenceFile(readText(testFiles.argyllColorCheckerCie), 'ColorChecker.cie', 'D50', '1931');
  assert.equal(T.parsePatchFile(readText(testFiles.argyllColorCheckerCie), 'ColorChecker.cie').format, 'cgats');
  assert.equal(cie.ids.length, 24);
  close(cie.Lab[0], 37.99, 1e-12, 'L of A1');
});

test('parseReferenceFile: malformed files give coded errors', async () => {
  const T = await loadTristim();
  throwsCode(assert, () => T.parseReferenceFile('patch,X,Y,Z\nA1,1,NaN,3\n', 'bad.csv', 'D65', '1931'), 'NON_FINITE');
  throwsCode(assert, () => T.parseReferenceFile('', 'empty.csv', 'D65', '1931'), 'EMPTY_FILE');
  throwsCode(assert, () => T.parseReferenceFile('patch,X,Y\nA1,1,2\n', 'x.csv', 'D65', '1931'), 'MISSING_COLUMN');
  throwsCode(assert, () => T.parseReferenceFile('patch,X,Y,Z\nA1,1,x,3\n', 'x.csv', 'D65', '1931'), 'NON_NUMERIC');
  throwsCode(assert, () => T.parseReferenceFile('wavelength,A1\n410,1\n400,1\n', 'x.csv', 'D65', '1931'), 'NON_MONOTONIC');
  throwsCode(assert, () => T.parseReferenceFile('patch,X,Y,Z\nA1,1,2,3\nA01,1,2,3\n', 'x.csv', 'D65', '1931'), 'DUPLICATE_ID');
  throwsCode(assert, () => T.parseReferenceFile('patch,X,Y,Z\nA1,1,2\n', 'x.csv', 'D65', '1931'), 'ROW_LENGTH');
  throwsCode(assert, () => T.parseReferenceFile('CTI3\nBEGIN_DATA_FORMAT\n', 'x.ti3', 'D65', '1931'), 'PARSE_ERROR');
  throwsCode(assert, () => T.referenceChart('cc99', 'D65', '1931'), 'UNKNOWN_ID');
  throwsCode(assert, () => T.referenceChart('cc24', 'D99', '1931'), 'UNKNOWN_ID');
  throwsCode(assert, () => T.referenceChart('cc24', 'D65', '1976'), 'UNKNOWN_ID');
  // The message names the line.
  assert.throws(() => T.parseReferenceFile('patch,X,Y,Z\nA1,1,2,3\nA2,1,inf,3\n', 'bad.csv', 'D65', '1931'), /line 3/);
});

test('spectralLocus and deltaE', async () => {
  const T = await loadTristim();
  const l = T.spectralLocus('1931');
  assert.equal(l.wavelengths.length, 471);
  assert.equal(l.x.length, 471);
  assert.equal(l.wavelengths[160], 520);
  close(l.x[160], 0.0743, 2e-4, 'x(520)');
  close(l.y[160], 0.8338, 2e-4, 'y(520)');
  // Sharma, Wu & Dalal (2005) pairs 1 and 2: 2.0425, 2.8615.
  const d = T.deltaE('CIE2000', new Float64Array([50, 2.6772, -79.7751, 50, 3.1571, -77.2803]),
    new Float64Array([50, 0, -82.7485, 50, 0, -82.7485]));
  assert.ok(d instanceof Float64Array);
  close(d[0], 2.0425, 1e-4, 'pair 1');
  close(d[1], 2.8615, 1e-4, 'pair 2');
  close(T.deltaE('CIE1976', [0, 0, 0], [3, 4, 0])[0], 5, 1e-12, 'dE76');
  throwsCode(assert, () => T.deltaE('CMC', [0, 0, 0], [0, 0, 0]), 'UNKNOWN_ID');
  throwsCode(assert, () => T.deltaE('CIE2000', [0, 0], [0, 0]), 'INVALID_ARGUMENT');
});

test('pairById and simulateCamera (the fit will pair simulated RGB with the reference)', async () => {
  const T = await loadTristim();
  const ref = T.referenceChart('cc24', 'D65', '1931');
  const sim = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D65', {});
  assert.equal(sim.RGB.length, 72);
  // Native `tristim simulate --camera "Canon EOS 5D Mark II" --reflectances cc24` row A1.
  close(sim.RGB[0], 0.05133642, 5e-9, 'R');
  close(sim.RGB[1], 0.07988166, 5e-9, 'G');
  const ids = [...sim.ids].reverse().map((id) => id.replace(/^([A-D])(\d)$/, '$10$2'));  // "A01" style, reversed
  const rgb = new Float64Array(72);
  for (let i = 0; i < 24; i++) rgb.set(sim.RGB.subarray(3 * (23 - i), 3 * (24 - i)), 3 * i);
  const p = T.pairById(ref.ids, ref.XYZ, ids, rgb);
  assert.deepEqual(p.ids, [...ref.ids].reverse());   // the measurement's order (the CLI's too)
  assert.deepEqual(Array.from(p.measured), Array.from(rgb));
  for (let i = 0; i < 24; i++) assert.deepEqual(Array.from(p.reference.subarray(3 * i, 3 * i + 3)), Array.from(ref.XYZ.subarray(3 * (23 - i), 3 * (24 - i))));
  assert.deepEqual(Array.from(p.reference_rows), ids.map((_, i) => 23 - i));
  assert.deepEqual(Array.from(p.measured_rows), ids.map((_, i) => i));
  throwsCode(assert, () => T.pairById(['A1'], [1, 2, 3], ['Z9'], [1, 2, 3]), 'PATCH_MISMATCH');
  const noisy = T.simulateCamera('Nikon_D850', 'cc24', 'D50', { noise_sigma: 1, seed: 5, oecf: true, oecf_gamma: 1.8, oecf_scale: 22, white_level: 80, clip_max: 255, quantise: true });
  for (const v of noisy.RGB) assert.equal(v, Math.round(v));
  throwsCode(assert, () => T.simulateCamera('Leica M3', 'cc24', 'D65', {}), 'UNKNOWN_ID');
});

test('display helpers: the white is white after adaptation, L*a*b* of the white is 100, 0, 0', async () => {
  const T = await loadTristim();
  const d50 = [96.422, 100, 82.521];
  for (const v of T.XYZToDisplaySRGB(Float64Array.from(d50), d50)) assert.ok(Math.abs(v - 1) < 1e-6, `white -> ${v}`);
  const lab = T.XYZToLab(Float64Array.from([...d50, ...d50.map((v) => v / 2)]), d50);
  assert.ok(Math.abs(lab[0] - 100) < 1e-9 && Math.abs(lab[1]) < 1e-9 && Math.abs(lab[2]) < 1e-9);
  assert.ok(Math.abs(lab[3] - 76.0693) < 1e-3, `half the white has L* ${lab[3]}`);
  // displayMatrix is the linear part of XYZToDisplaySRGB: the white maps to (1, 1, 1).
  const M = T.displayMatrix(d50);
  for (let r = 0; r < 3; r++) {
    const v = M[3 * r] * d50[0] + M[3 * r + 1] * d50[1] + M[3 * r + 2] * d50[2];
    assert.ok(Math.abs(v - 1) < 1e-9, `row ${r}: ${v}`);
  }
  throwsCode(assert, () => T.XYZToLab(new Float64Array(4), d50), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.displayMatrix([1, 2]), 'INVALID_ARGUMENT');
});

// Camera spectral sensitivities in wasm (eq 7's channel areas, Guarnera 2018; Jiang, Liu, Gu &
// Süsstrunk 2013): a built-in camera's curves through the CSV writer and the core's parser
// (ratios kept), the estimate from a simulated ColorChecker photo under D65 with the camera held
// out of the basis (area ratios within the 2 %), pairing by patch id, a given set feeding
// the absolute fit (same areas as the built-in camera, source recorded in the profile), coded
// errors for bad CSVs and unpaired patches, and the estimate and its uncertainty equal to the CLI's
// JSON to the bit.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { loadTristim, throwsCode } from './load.mjs';
import { absoluteFixture } from '../support/absolute_fixture.mjs';

const CAMERA = 'Canon_EOS_5D_Mark_II';
const rel = (a, b) => Math.abs(a / b - 1);

test('sensitivities: a built-in camera through sensitivitiesToCsv and readSensitivitiesCsv keeps its channel ratios', async () => {
  const T = await loadTristim();
  const cam = T.cameraSensitivities(CAMERA);
  assert.deepEqual(Array.from(cam.names), ['R', 'G', 'B']);
  assert.equal(cam.wavelengths[0], 380);
  const csv = T.sensitivitiesToCsv(cam);
  assert.match(csv, /^wavelength_nm,R,G,B\n380,/);
  const back = T.readSensitivitiesCsv(csv, 'camera.csv');
  assert.equal(back.values.length, 3);
  assert.equal(back.wavelengths.length, cam.wavelengths.length);
  const peak = Math.max(...back.values.map((v) => Math.max(...v)));
  assert.ok(Math.abs(peak - 1) < 1e-9, `peak ${peak}`);
  const a = T.channelAreas(cam), b = T.channelAreas(back);
  assert.ok(rel(b[0] / b[1], a[0] / a[1]) < 1e-7 && rel(b[2] / b[1], a[2] / a[1]) < 1e-7, `${b} vs ${a}`);
  assert.ok(T.sensitivityRms(back, cam) < 1e-7);
});

test('sensitivities: estimated from a simulated ColorChecker under D65, the camera held out of the basis', async () => {
  const T = await loadTristim();
  const truth = T.cameraSensitivities(CAMERA);
  const chart = T.simulateCamera(CAMERA, 'cc24', 'D65', {});
  // rows reversed: pairing is by patch id, not order
  const n = chart.ids.length, ids = [...chart.ids].reverse(), rgb = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) rgb.set(chart.RGB.subarray(3 * (n - 1 - i), 3 * (n - i)), 3 * i);
  const e = T.estimateSensitivities(ids, rgb, T.chartReflectances('cc24'), T.illuminantSpectrum('D65'), { exclude_cameras: [CAMERA] });
  assert.equal(e.patches, 24);
  assert.equal(e.unpaired, 0);
  assert.equal(e.basis_cameras, 51);
  assert.deepEqual(Array.from(e.ids), ids);
  assert.ok(e.residual_rms > 0 && e.residual_rms < 0.02, `residual ${e.residual_rms}`);
  const A = T.channelAreas(truth);
  const rR = rel(e.areas[0] / e.areas[1], A[0] / A[1]), rB = rel(e.areas[2] / e.areas[1], A[2] / A[1]);
  assert.ok(rR < 0.02 && rB < 0.02, `area ratios off by ${rR}, ${rB}`);
  const rms = T.sensitivityRms(e.ssf, truth);
  assert.ok(rms < 0.06, `RMS (each channel at peak 1) ${rms}`);
  // in the basis: nearly exact
  const inBasis = T.estimateSensitivities(chart.ids, chart.RGB, T.chartReflectances('cc24'), T.illuminantSpectrum('D65'));
  assert.ok(T.sensitivityRms(inBasis.ssf, truth) < rms, 'a camera in the basis is recovered better than a held-out one');
});

test('sensitivities: a given set feeds the absolute fit (areas as the built-in camera, source in the profile)', async () => {
  const T = await loadTristim();
  const ex = T.absoluteExample({ seed: 1, cell: 12 });   // small frames: three fits follow
  const stimuli = T.readAbsoluteStimuli(ex.stimuli_csv, 'example.csv');
  // The absolute recipe as the page makes it (the example's files), with each choice of sensitivities.
  const fit = (sensitivities) => T.fitAbsolute({ inputs: { stimuli, bracket: ex.frame_names, lens_cap: ex.lens_cap_names, flat: ex.flat_name, sensitivities } },
    { bracket: ex.frames, lens_cap: ex.lens_cap, flat: ex.flat }).report.fit;
  try {
    const uploaded = T.readSensitivitiesCsv(T.sensitivitiesToCsv(T.cameraSensitivities(ex.camera)), 'ssf.csv');
    const givenFit = T.fitAbsolute({ inputs: { stimuli, bracket: ex.frame_names, lens_cap: ex.lens_cap_names, flat: ex.flat_name,
      sensitivities: { choice: 'given', wavelengths: uploaded.wavelengths, R: uploaded.values[0], G: uploaded.values[1], B: uploaded.values[2], source: 'file:ssf.csv' } } }, { bracket: ex.frames, lens_cap: ex.lens_cap, flat: ex.flat });
    const given = givenFit.report.fit;
    const builtIn = fit({ choice: 'camera', camera: ex.camera });
    assert.equal(given.areas_source, 'file:ssf.csv');
    assert.equal(JSON.parse(givenFit.profile).areas_source ?? JSON.parse(givenFit.profile).normalisation?.areas_source, 'file:ssf.csv');
    for (let c = 0; c < 3; c++) assert.ok(rel(given.areas[c] / given.areas[1], builtIn.areas[c] / builtIn.areas[1]) < 1e-6, `area ${c}`);
    const none = fit({ choice: 'none' });
    assert.equal(none.areas_source, 'none');
    assert.ok(rel(none.areas[0] / none.areas[1], builtIn.areas[0] / builtIn.areas[1]) > 0.01, 'the sensitivities change the areas');
  } finally {
    for (const f of [...ex.frames, ...ex.lens_cap, ex.flat]) f.delete();
  }
});

test('sensitivities: coded errors for bad CSVs, unknown cameras and unpaired patches', async () => {
  const T = await loadTristim();
  throwsCode(assert, () => T.readSensitivitiesCsv('wavelength_nm,R,G,X,Y\n400,1,2,3,4\n410,1,2,3,4\n', 'five.csv'), 'MISSING_COLUMN');
  throwsCode(assert, () => T.readSensitivitiesCsv('wavelength_nm,R,G,B\n410,1,2,3\n400,1,2,3\n', 'order.csv'), 'NON_MONOTONIC');
  throwsCode(assert, () => T.readSensitivitiesCsv('wavelength_nm,R,G,B\n', 'empty.csv'), 'EMPTY_FILE');
  throwsCode(assert, () => T.channelAreas(T.readSensitivitiesCsv('wavelength_nm,R,G,B\n400,1,0,3\n410,1,0,3\n', 'zero.csv')), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.cameraSensitivities('Leica M3'), 'UNKNOWN_ID');
  const refl = T.chartReflectances('cc24'), d65 = T.illuminantSpectrum('D65');
  throwsCode(assert, () => T.estimateSensitivities(['Z1', 'Z2'], new Float64Array(6).fill(1), refl, d65), 'PATCH_MISMATCH');
  throwsCode(assert, () => T.estimateSensitivities(['A1'], new Float64Array(6).fill(1), refl, d65), 'PATCH_MISMATCH');
  throwsCode(assert, () => T.illuminantSpectrum('D1'), 'UNKNOWN_ID');
});

// ---- one field list: the uncertainty the page shows is what `tristim sensitivities estimate` prints
const { dir: fixture, cli } = absoluteFixture('tristim-sensitivities-');

test('sensitivities: the module\'s estimate and its uncertainty equal the CLI\'s JSON, to the bit (SensitivityEstimate\'s and SensitivityUncertainty\'s lists)', async () => {
  const T = await loadTristim();
  const dir = fixture();
  const printed = JSON.parse(cli(dir, ['sensitivities', 'estimate', '--rgb', 'patches_rgb.csv', '--reflectances', 'cc24', '--illuminant', 'D65',
    '--exclude', CAMERA, '--out', 'ssf.csv']));
  // as the page's handler does (web/absolute/sensitivities_handlers.js): the patch file, a chart, an illuminant
  const p = T.parsePatchFile(fs.readFileSync(path.join(dir, 'patches_rgb.csv'), 'utf8'), 'patches_rgb.csv');
  const spd = T.illuminantSpectrum('D65'), options = { exclude_cameras: [CAMERA] };
  const e = T.estimateSensitivities(p.ids, p.RGB, T.chartReflectances('cc24'), spd, options);
  const refl = T.chartReflectances('cc24');
  const u = T.sensitivityUncertainty(p.ids, p.RGB, refl, spd, options, e);
  assert.deepStrictEqual(u, printed.uncertainty);
  // the estimate itself is the CLI's JSON without its extras (SensitivityEstimate's list)
  const { uncertainty, ...estimate } = printed;
  assert.deepStrictEqual(e, estimate);
  assert.ok(Array.isArray(e.ssf.values[0]) && Array.isArray(e.residual), 'plain Arrays, as the JSON has them');
  // handed back, it is read by the list: an unknown member refused, the CLI's old names too
  throwsCode(assert, () => T.sensitivityUncertainty(p.ids, p.RGB, refl, spd, options, { ...e, clipped_samples: 0 }), 'INVALID_ARGUMENT');
  assert.ok(Array.isArray(u.ratio) && Array.isArray(u.u), 'plain Arrays, as the JSON has them');
  assert.equal(u.ratio[0], printed.area_ratio_R_G);
});

// The surface stage in wasm (Abed, Berns & Masaoka 2013): presets, a correction applied, Phase I
// and Phase II recovering planted coefficients, the corrected 3×3, the simulated Table IV, the
// real two-geometry SG data, and coded errors for bad input.
import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, readText, throwsCode } from './load.mjs';

const near = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (tolerance ${tol})`);
const SG = 'sg140-2005';

test('listSurfacePresets: literature geometries with their sources', async () => {
  const T = await loadTristim();
  const p = Object.fromEntries(T.listSurfacePresets().map((r) => [r.id, r]));
  assert.deepEqual(p['d8-sci'].geometry, { k1: 0.092, k2: 0.6, k_ins: 1 });
  assert.deepEqual(p['45-0'].geometry, { k1: 0.04, k2: 0.6, k_ins: 0 });
  assert.equal(p['d8-sci'].role, 'measurement');
  for (const r of Object.values(p)) assert.ok(r.source.length > 10, `${r.id} cites a source`);
  assert.deepEqual(T.surfaceTable4Methods(), ['scaler-offset', 'saunderson', 'matrix-3x3', 'matrix-3x4', 'corrected-3x3']);
});

test('correctSurface: eq (5) on every value; the choice text reads back', async () => {
  const T = await loadTristim();
  const refl = T.chartReflectances(SG);
  const out = T.correctSurface('scaler-offset:mu=1.05,rho=-0.03', refl);
  assert.deepEqual(out.names, refl.names);
  for (const c of [0, 17, 139]) for (const w of [0, 10, 30]) near(out.values[c][w], 1.05 * refl.values[c][w] - 0.03, 1e-15, `${c}/${w}`);
  const choice = { method: 'scaler-offset', parameters: { mu: 1.05, rho: -0.03 }, settings: {} };
  assert.equal(T.surfaceChoiceText(choice), 'scaler-offset:mu=1.05,rho=-0.03');
  assert.deepEqual(T.parseChoice(T.surfaceChoiceText(choice)).parameters, choice.parameters);
});

test('fitSurface (Phase I): planted scaler-offset and Saunderson coefficients are recovered', async () => {
  const T = await loadTristim();
  const measured = T.chartReflectances(SG);
  const so = T.fitSurface('scaler-offset', measured, T.correctSurface('scaler-offset:mu=0.95,rho=0.03', measured),
    { range_min: 400, range_max: 700 }, 'D50');
  near(so.choice.parameters.mu, 0.95, 1e-5, 'mu');
  near(so.choice.parameters.rho, 0.03, 1e-5, 'rho');
  assert.ok(so.dE00.after.mean < 1e-3 && so.dE00.before.mean > 1, `ΔE00 ${so.dE00.before.mean} -> ${so.dE00.after.mean}`);
  assert.equal(so.patches.length, 140);
  assert.equal(so.wavelengths[0], 400);
  assert.equal(so.corrected.values.length, 140);

  // 45:0 instrument fixed, capture coefficients planted (a diffuse booth seeing part of the gloss)
  const truth = 'saunderson:k1=0.04,k2=0.6,k_ins=0,k1_capture=0.092,k2_capture=0.6,k_ins_capture=0.5';
  const target = T.correctSurface(truth, measured);
  const sa = T.fitSurface('saunderson:k1=0.04,k2=0.6,k_ins=0', measured, target, { range_min: 400, range_max: 700 });
  assert.deepEqual(sa.free, ['k1_capture', 'k2_capture', 'k_ins_capture']);
  assert.ok(sa.spectral_rms.after < 1e-5, `rms ${sa.spectral_rms.after}`);
  near(sa.dE00.after.max, 0, 0.01, 'max ΔE00 after');
});

test('fitSurfaceJoint (Phase II): a colorimetric camera, anchored to the white, recovers μ and ρ', async () => {
  const T = await loadTristim();
  const reflectances = T.chartReflectances(SG);
  const seen = T.recipeReference({ reference: { chart: SG, illuminant: 'D50', observer: '1931' }, surface: { method: 'scaler-offset', parameters: { mu: 1.04, rho: -0.02 } } });
  // camera RGB = A⁻¹·XYZ for an invertible A (a camera whose sensitivities are CMF combinations)
  const Ainv = [[0.9, 0.2, -0.1], [-0.3, 1.2, 0.1], [0.05, -0.1, 1.1]];
  const cam = (x, y, z) => Ainv.map((r) => r[0] * x + r[1] * y + r[2] * z);
  const rgb = new Float64Array(seen.XYZ.length);
  for (let i = 0; i < seen.XYZ.length; i += 3) rgb.set(cam(seen.XYZ[i], seen.XYZ[i + 1], seen.XYZ[i + 2]), i);
  const white_RGB = cam(...seen.white);   // a Lambertian white, R_w = 1
  const r = T.fitSurfaceJoint('scaler-offset', rgb, reflectances, { white_RGB, white_reflectance: 1 }, 'D50');
  near(r.choice.parameters.mu, 1.04, 1e-3, 'mu');
  near(r.choice.parameters.rho, -0.02, 1e-3, 'rho');
  assert.ok(r.dE_xyz_rms < 0.01 && r.dE_xyz_rms_start > 1, `ΔE_xyz ${r.dE_xyz_rms_start} -> ${r.dE_xyz_rms}`);
  assert.equal(r.matrix.length, 9);   // row-major, as `tristim surface joint --json` prints it
  // the anchor: the matrix maps the white's RGB onto the illuminant's white exactly
  for (let k = 0; k < 3; k++) near(r.matrix.slice(3 * k, 3 * k + 3).reduce((a, m, c) => a + m * white_RGB[c], 0), seen.white[k], 1e-8, `white ${'XYZ'[k]}`);
  throwsCode(assert, () => T.fitSurfaceJoint('scaler-offset', rgb, reflectances, {}, 'D50'), 'INVALID_ARGUMENT');   // no white
});

test('fitCorrected3x3 (eqs 6-13): planted M\', offset and μ', async () => {
  const T = await loadTristim();
  const M = [[0.6, 0.3, 0.1], [0.25, 0.7, 0.05], [0.02, 0.1, 0.9]], off = [0.5, 0.4, 0.3], mu = 0.93;
  const rgb = [], xyz = [];
  for (let i = 0; i < 20; i++) {
    const c = [(i * 37) % 97 + 1, (i * 53) % 89 + 2, (i * 71) % 83 + 3];
    rgb.push(...c);
    xyz.push(...M.map((r, k) => r[0] * c[0] + r[1] * c[1] + r[2] * c[2] + off[k]));
  }
  const wRGB = [100, 100, 100], wXYZ = M.map((r) => mu * (r[0] + r[1] + r[2]) * 100);
  const c = T.fitCorrected3x3(rgb, xyz, wRGB, wXYZ);
  near(c.mu, mu, 1e-9, 'μ');
  assert.equal(c.matrix_3x4.length, 12);
  near(c.matrix_3x4[3], off[0], 1e-8, 'offset X');
  near(c.matrix[4], mu * M[1][1], 1e-9, 'M_cr[1][1]');
});

test('surfaceTable4: the simulated Table IV, surface-corrected methods beat the 3×3 and 3×4 trained on SG', async () => {
  const T = await loadTristim();
  const cells = T.surfaceTable4('Nikon_D850', 'D50', 0.001, 1);
  assert.equal(cells.length, 20);
  for (const c of cells) assert.ok(c.ok, `${c.training}/${c.method}: ${c.message}`);
  const mean = (training, method) => cells.find((c) => c.training === training && c.method === method).dE00.mean;
  for (const m of ['scaler-offset', 'saunderson', 'corrected-3x3'])
    for (const plain of ['matrix-3x3', 'matrix-3x4']) assert.ok(mean('SG', m) < mean('SG', plain), `SG: ${m} ${mean('SG', m)} vs ${plain} ${mean('SG', plain)}`);
});

test('real data: the SG in two geometries (d:8 SCI -> X-Rite), the paper\'s ranking on mean CIEDE2000', async () => {
  const T = await loadTristim();
  const sci = T.parsePatchFile(readText('examples/web/sg_d8_sci_coolpi.csv'), 'XRCCSG.csv');
  assert.ok(sci.has_spectra);
  const xrite = T.chartReflectances(SG);
  const o = { range_min: 400, range_max: 700 };
  const mean = Object.fromEntries(['none', 'scaler', 'offset', 'scaler-offset'].map((m) =>
    [m, T.fitSurface(m, sci.spectra, xrite, o, 'D50').dE00.after.mean]));
  mean.saunderson = T.fitSurface('saunderson:k1=0.092,k2=0.6,k_ins=1,k1_capture=0.04,k2_capture=0.6,k_ins_capture=0',
    sci.spectra, xrite, { ...o, free: 'measurement' }, 'D50').dE00.after.mean;
  // the native figures (examples/surface/sg_two_geometries.py): 4.62, 4.43, 1.91, 1.51, 1.13
  near(mean.none, 4.62, 0.01, 'none');
  near(mean.offset, 1.91, 0.01, 'offset');
  near(mean.saunderson, 1.13, 0.01, 'saunderson');
  assert.ok(Math.abs(mean.scaler - mean.none) < 0.15 * mean.none && mean.offset < mean.scaler
    && mean['scaler-offset'] < mean.offset && mean.saunderson <= mean['scaler-offset'], JSON.stringify(mean));
});

test('coded errors for bad input', async () => {
  const T = await loadTristim();
  const refl = T.chartReflectances(SG);
  throwsCode(assert, () => T.correctSurface('scaler:mu=3', refl), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.correctSurface('shiny', refl), 'UNKNOWN_ID');
  const negative = { ...refl, values: refl.values.map((c, i) => (i === 3 ? c.map(() => -0.1) : c)) };
  throwsCode(assert, () => T.correctSurface('offset', negative), 'NEGATIVE_VALUE');
  const fewer = { ...refl, names: refl.names.slice(0, 20), values: refl.values.slice(0, 20) };
  throwsCode(assert, () => T.fitSurface('offset', refl, fewer), 'PATCH_MISMATCH');
  throwsCode(assert, () => T.fitSurface('saunderson', refl, refl, { free: 'k1+k2+k_ins+k1_capture' }), 'ILL_POSED');
  throwsCode(assert, () => T.fitSurface('offset', refl, refl, { range_min: 300, range_max: 800 }), 'WAVELENGTH_MISMATCH');
  throwsCode(assert, () => T.fitSurface('offset', refl, refl, { shiny: 1 }), 'INVALID_ARGUMENT');
});

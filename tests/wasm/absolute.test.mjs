// The absolute tele-colorimeter in wasm (Guarnera, Bianco & Schettini 2018): the virtual-camera
// example (brackets with a planted power-law OECF, S below LibRaw's claim, fall-off, shot noise)
// fitted from its stimuli CSV, lens-cap frames and flat, applied to the bracket: planted OECF
// exponents and S recovered, every cell's Y within the paper's 2.4 %, the pointer read-out, and
// coded errors for mismatched brackets, an all-dark series and non-monotonic stimuli.
import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, throwsCode } from './load.mjs';

const near = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (tolerance ${tol})`);
const del = (...hs) => { for (const h of hs.flat()) h?.delete(); };

let cached = null;
async function example(T) {
  if (cached) return cached;
  const ex = T.absoluteExample({ seed: 1 });
  const stimuli = T.readAbsoluteStimuli(ex.stimuli_csv, 'example.csv');
  const fit = T.fitAbsolute({ stimuli, camera: ex.camera }, [], ex.lens_cap, [ex.flat], ex.frames);
  cached = { ex, stimuli, fit };
  return cached;
}

test('absolute fit on the example: planted OECF exponents, S measured below the metadata, reciprocity holds', async () => {
  const T = await loadTristim();
  const { ex, stimuli, fit } = await example(T);
  assert.equal(ex.frames.length, 5);
  assert.equal(ex.frames[0].width(), 192);
  assert.ok(stimuli.length > 130, `${stimuli.length} stimuli`);
  assert.equal(stimuli.filter((s) => s.set === 'colour').length, 24);
  // the virtual sensor: OECF exponents 1.03, 1, 0.97 (R' = (k2·H)^k3), clip at 15000 DN, metadata 16000
  near(fit.channels[0].k3, 1.03, 0.01, 'k3 R');
  near(fit.channels[1].k3, 1.0, 0.01, 'k3 G');
  near(fit.channels[2].k3, 0.97, 0.01, 'k3 B');
  for (let c = 0; c < 3; c++) {
    assert.ok(fit.saturation_measured[c], `S measured in channel ${c}`);
    near(fit.saturation[c], 15000, 2, `S channel ${c}`);
    near(fit.saturation_fraction[c], 15000 / 16000, 2e-4, `saturation fraction ${c}`);
  }
  assert.ok(fit.reciprocity_ok, fit.reciprocity_message);
  assert.equal(fit.panels.length, 5);
  assert.equal(fit.panels[0].label, ex.labels[0]);
  for (const p of fit.panels) for (let c = 0; c < 3; c++) {
    assert.ok(p.point_Y[c].length >= 3 && p.point_Y[c].length === p.point_R[c].length, `${p.label} ch ${c} points`);
    assert.ok(p.curve_Y[c].length > 10 && p.curve_Y[c].length === p.curve_R[c].length);
  }
  assert.ok(fit.has_falloff && fit.falloff.p1 > 0.2, `fall-off p1 ${fit.falloff.p1}`);
  assert.equal(fit.areas_source, `camera:${ex.camera}`);
  assert.equal(fit.colour_stimuli, 24);
  assert.equal(fit.make, ex.make);
  assert.ok(fit.training.relative_Y_error < 0.024, `training relative Y error ${fit.training.relative_Y_error}`);
  assert.ok(typeof fit.profile === 'string' && fit.profile.includes('tristim-absolute-profile'));
});

test('applyAbsolute on the bracket: Y within 2.4 %, the read-out, the source exposures', async () => {
  const T = await loadTristim();
  const { ex, fit } = await example(T);
  const seen = [];
  const maps = T.applyAbsolute(fit.profile, ex.frames, {}, (f, stage) => seen.push([f, stage]));
  try {
    assert.ok(seen.length >= 5 && /fusing 1\/250 s/.test(seen[0][1]), JSON.stringify(seen));
    const s = maps.summary();
    assert.equal(s.width, 192);
    assert.equal(s.height, 192);
    assert.equal(s.labels.length, 5);
    assert.equal(maps.XYZ().length, 3 * 192 * 192);
    assert.equal(maps.source().length, 192 * 192);
    // the float TIFF holds the XYZ map as it is (little-endian float32 at StripOffsets)
    const tiff = maps.tiff(), xyz = maps.XYZ();
    assert.ok(tiff instanceof Uint8Array);
    const dv = new DataView(tiff.buffer, tiff.byteOffset, tiff.byteLength), ifd = dv.getUint32(4, true);
    let strip = -1;
    for (let i = 0; i < dv.getUint16(ifd, true); i++) if (dv.getUint16(ifd + 2 + 12 * i, true) === 273) strip = dv.getUint32(ifd + 2 + 12 * i + 8, true);
    assert.ok(strip > 0 && strip + 4 * xyz.length <= tiff.length);
    for (const i of [0, 1, 2, 3 * 96 * 192 + 4, xyz.length - 1]) assert.ok(Object.is(dv.getFloat32(strip + 4 * i, true), xyz[i]), `TIFF sample ${i}`);
    const white = ex.regions.find((r) => r.id === ex.white_id);
    const yMax = Math.max(...ex.regions.map((r) => r.XYZ[1]));
    const w = T.whiteGuarnera2018(white.XYZ, yMax);
    near(w[1], yMax, 1e-9, 'eq 16 white Y');
    const fig = maps.measure(ex.regions, w);
    // equal-tristimulus cells (the luminance module, eq 9) one by one; the chart's colours, which also
    // go through M trained on projector primaries, on average
    for (let i = 0; i < fig.ids.length; i++) {
      const yRef = fig.reference[3 * i + 1];
      if (/^E/.test(fig.ids[i])) assert.ok(Math.abs(fig.relative_Y[i]) < (yRef < 1 ? 0.05 : 0.024), `${fig.ids[i]}: Y ${fig.estimated[3 * i + 1]} vs ${yRef}`);
    }
    assert.ok(fig.metrics.relative_Y_error < 0.024, `relative Y error ${fig.metrics.relative_Y_error}`);
    assert.ok(fig.metrics.metrics.NRMSE[1] < 0.016, `NRMSE Y ${fig.metrics.metrics.NRMSE[1]}`);
    // up the ladder the dominant exposure gets shorter: the darkest cell from the longest (1/15 s),
    // the brightest (3000 cd/m²) from one of the two shortest
    const k = (id) => fig.ids.indexOf(id);
    const ladder = ex.regions.filter((r) => /^E/.test(r.id)).map((r) => fig.source[k(r.id)]);
    assert.equal(ladder[0], 4);
    assert.ok(ladder.at(-1) <= 1, `brightest cell served by exposure ${ladder.at(-1)}`);
    for (let i = 1; i < ladder.length; i++) assert.ok(ladder[i] <= ladder[i - 1], `ladder sources ${ladder}`);
    // pointer read-out at a cell's centre: the known stimulus, the exposure that served it
    const g = ex.regions.find((r) => r.id === ex.white_id);
    const r = maps.readout(g.x + g.w / 2, g.y + g.h / 2, 5);
    assert.equal(r.n, 25);
    for (let c = 0; c < 3; c++) near(r.XYZ[c] / g.XYZ[c], 1, 0.024, `read-out ${'XYZ'[c]} of ${g.id}`);
    assert.ok(r.source >= 0 && r.source_label === s.labels[r.source], JSON.stringify(r));
    assert.ok(r.contributors.includes(r.source));
    throwsCode(assert, () => maps.readout(-1, 0, 1), 'INVALID_ARGUMENT');
  } finally { maps.delete(); }
  // Algorithm 1 (recursive selection) agrees within the same bound
  const rec = T.applyAbsolute(fit.profile, ex.frames, { mode: 'recursive' });
  try {
    const white = T.whiteEqualEnergy(3000);
    const fig = rec.measure(ex.regions.filter((r) => r.XYZ[1] >= 1), white);
    assert.ok(fig.metrics.relative_Y_error < 0.024, `Algorithm 1 relative Y error ${fig.metrics.relative_Y_error}`);
  } finally { rec.delete(); }
});

test('absolute: mismatched brackets, a dark series, non-monotonic stimuli and bad CSVs are coded errors', async () => {
  const T = await loadTristim();
  const { ex, fit } = await example(T);
  const small = T.absoluteExample({ cell: 16, seed: 2 });
  const nikon = T.absoluteExample({ camera: 'Nikon_D850', cell: 32, seed: 3 });
  try {
    // another size in the series
    throwsCode(assert, () => T.applyAbsolute(fit.profile, [ex.frames[0], small.frames[1]], { names: ['a.dng', 'b.dng'] }), 'FRAME_MISMATCH');
    // another camera (than the profile's, and than the series')
    throwsCode(assert, () => T.applyAbsolute(fit.profile, [nikon.frames[0]]), 'FRAME_MISMATCH');
    throwsCode(assert, () => T.fitAbsolute({ stimuli: T.readAbsoluteStimuli(ex.stimuli_csv, 's.csv') }, [], ex.lens_cap, [], [ex.frames[0], nikon.frames[1]]), 'FRAME_MISMATCH');
    // lens-cap frames only: nothing reliable in any exposure
    throwsCode(assert, () => T.applyAbsolute(fit.profile, ex.lens_cap), 'NO_USABLE_DATA');
    // non-monotonic: a brighter luminance stimulus reads lower than a dimmer one at the same exposure
    const rows = ex.stimuli_csv.trim().split('\n');
    const header = rows[0].split(','), col = (n) => header.indexOf(n);
    const at = (id) => rows.findIndex((r) => r.startsWith(`${id},`));
    const a = rows[at('Y300@3')].split(','), b = rows[at('Y600@3')].split(',');
    for (const c of ['R', 'G', 'B']) [a[col(c)], b[col(c)]] = [b[col(c)], a[col(c)]];
    rows[at('Y300@3')] = a.join(','); rows[at('Y600@3')] = b.join(',');
    const bad = T.readAbsoluteStimuli(rows.join('\n'), 'swapped.csv');
    throwsCode(assert, () => T.fitAbsolute({ stimuli: bad, camera: ex.camera }, [], ex.lens_cap, [ex.flat], ex.frames), 'NON_MONOTONIC');
    throwsCode(assert, () => T.readAbsoluteStimuli('id,R,G,B\n1,2,3,4\n', 'no-xyz.csv'), 'MISSING_COLUMN');
    throwsCode(assert, () => T.readAbsoluteStimuli('id,R,G,B,X,Y,Z\n1,2,3,4,5,5,5\n', 'no-exposure.csv'), 'MISSING_METADATA');
    // per-patch stimuli with neither S nor frames to measure it from
    throwsCode(assert, () => T.fitAbsolute({ stimuli: T.readAbsoluteStimuli(ex.stimuli_csv, 's.csv') }), 'INVALID_ARGUMENT');
    throwsCode(assert, () => T.applyAbsolute('{"format":"tristim-absolute-profile","version":7}', ex.frames), 'PROFILE_VERSION');
    throwsCode(assert, () => T.absoluteExample({ camera: 'No_Such_Camera' }), 'UNKNOWN_ID');
  } finally {
    del(small.frames, small.lens_cap, small.flat, nikon.frames, nikon.lens_cap, nikon.flat);
  }
});

test('absolute example under F2 with reflective colour training: SG colours under the scene light, T2R meets Table 4 on the chart', async () => {
  const T = await loadTristim();
  const ex = T.absoluteExample({ illuminant: 'F2', colour_training: 'reflective', cell: 16, seed: 4 });
  let maps = null;
  try {
    const stimuli = T.readAbsoluteStimuli(ex.stimuli_csv, 'f2.csv');
    const colour = stimuli.filter((s) => s.set === 'colour');
    assert.ok(colour.length > 60, `${colour.length} colour stimuli`);
    assert.ok(colour.every((s) => /^colour SG /.test(s.id)), colour[0].id);
    const fit = T.fitAbsolute({ stimuli, camera: ex.camera, transform: 'T2R' }, [], ex.lens_cap, [ex.flat], ex.frames);
    maps = T.applyAbsolute(fit.profile, ex.frames);
    const cells = ex.regions.filter((r) => r.id[0] !== 'E');
    const white = ex.regions.find((r) => r.id === ex.white_id);
    const yMax = Math.max(...ex.regions.map((r) => r.XYZ[1]));
    const m = maps.measure(cells, T.whiteGuarnera2018(white.XYZ, yMax));
    assert.ok(m.metrics.relative_Y_error < 0.024, `F2, reflective training, T2R: relative Y error ${m.metrics.relative_Y_error}`);
    const nrmse = Array.from(m.metrics.metrics.NRMSE).reduce((a, b) => a + b) / 3;
    assert.ok(nrmse < 0.013, `F2, reflective training, T2R: mean NRMSE ${nrmse} (Table 4, multi-shot: 1.3 %)`);
  } finally {
    maps?.delete();
    del(ex.frames, ex.lens_cap, ex.flat);
  }
  throwsCode(assert, () => T.absoluteExample({ colour_training: 'printed' }), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.absoluteExample({ illuminant: 'D1' }), 'UNKNOWN_ID');
});

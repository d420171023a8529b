// The absolute tele-colorimeter in wasm (Guarnera, Bianco & Schettini 2018): the virtual-camera
// example (brackets with a planted power-law OECF, S below LibRaw's claim, fall-off, shot noise)
// fitted from its stimuli CSV, lens-cap frames and flat, applied to the bracket: planted OECF
// exponents and S recovered, every cell's Y within the paper's 2.4 %, the pointer read-out, and
// coded errors for mismatched brackets, an all-dark series and non-monotonic stimuli; the module's
// profile, report, maps summary and read-out equal `tristim absolute fit`, `tristim absolute evaluate
// --json` and `tristim absolute apply --points` to the bit on the example and on test scenes of region rows.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { loadTristim, throwsCode } from './load.mjs';
import { absoluteFixture } from '../support/absolute_fixture.mjs';

const near = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (tolerance ${tol})`);
const del = (...hs) => { for (const h of hs.flat()) h?.delete(); };

/// The absolute recipe of an example as the page makes it (the files its frames stand for), and its frames.
const recipeOf = (ex, stimuli, options = {}) => ({
  inputs: { stimuli, bracket: ex.frame_names, lens_cap: ex.lens_cap_names, flat: ex.flat_name, sensitivities: { choice: 'camera', camera: ex.camera } }, options });
const framesOf = (ex) => ({ bracket: ex.frames, lens_cap: ex.lens_cap, flat: ex.flat });

let cached = null;
async function example(T) {
  if (cached) return cached;
  const ex = T.absoluteExample({ seed: 1 });
  const stimuli = T.readAbsoluteStimuli(ex.stimuli_csv, 'example.csv');
  const fit = T.fitAbsolute(recipeOf(ex, stimuli), framesOf(ex));
  cached = { ex, stimuli, fit };
  return cached;
}

test('absolute fit on the example: planted OECF exponents, S measured below the metadata, reciprocity holds', async () => {
  const T = await loadTristim();
  const { ex, stimuli, fit: outcome } = await example(T);
  const fit = outcome.report.fit, panels = outcome.panels;
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
  assert.equal(panels.length, 5);
  assert.equal(panels[0].label, ex.labels[0]);
  for (const p of panels) for (let c = 0; c < 3; c++) {
    assert.ok(p.point_Y[c].length >= 3 && p.point_Y[c].length === p.point_R[c].length, `${p.label} ch ${c} points`);
    assert.ok(p.curve_Y[c].length > 10 && p.curve_Y[c].length === p.curve_R[c].length);
  }
  assert.ok(fit.falloff && fit.falloff.p1 > 0.2, `fall-off p1 ${fit.falloff.p1}`);
  assert.equal(fit.areas_source, `camera:${ex.camera}`);
  assert.equal(fit.colour_stimuli, 24);
  assert.equal(fit.make, ex.frames[0].metadata().make);
  const training = outcome.report.training.figures;
  assert.ok(training.relative_Y_error < 0.024, `training relative Y error ${training.relative_Y_error}`);
  assert.ok(typeof outcome.profile === 'string' && outcome.profile.includes('tristim-absolute-profile'));
  // the profile embeds the completed recipe: the example's files, every row's set, the options
  const embedded = JSON.parse(outcome.profile).recipe;
  assert.deepEqual(embedded.inputs.bracket, ex.frame_names);
  assert.equal(embedded.inputs.stimuli.length, stimuli.length);
  assert.equal(embedded.options.w, 10);
  assert.equal(T.absoluteRecipeToJson(outcome.recipe), T.absoluteRecipeToJson(T.absoluteRecipeFromJson(T.absoluteRecipeToJson(outcome.recipe))));
});

test('applyAbsolute on the bracket: Y within 2.4 %, the read-out, the source exposures', async () => {
  const T = await loadTristim();
  const { ex, fit } = await example(T);
  const test = T.readAbsoluteStimuli(ex.test_csv, 'test.csv');
  const seen = [];
  const maps = T.applyAbsolute(fit.profile, ex.frames, { names: ex.frame_names }, (f, stage) => seen.push([f, stage]));
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
    const report = maps.report(test, { white: ex.white_id }), fig = report.test;
    assert.deepEqual(fig.white, Array.from(w));
    assert.equal(fig.white_rule, 'eq16');
    assert.deepEqual(maps.report(test).test.white, fig.white, 'the engine takes the brightest chromatic stimulus, the white patch');
    assert.deepEqual(maps.summary(), report.maps, 'the maps summary crosses as the report\'s JSON has it');
    // equal-tristimulus cells (the luminance module, eq 9) one by one; the chart's colours, which also
    // go through M trained on projector primaries, on average
    for (const r of fig.regions) {
      if (r.set === 'luminance') assert.ok(Math.abs(r.relative_Y_error) < (r.reference[1] < 1 ? 0.05 : 0.024), `${r.id}: Y ${r.estimated[1]} vs ${r.reference[1]}`);
    }
    assert.deepEqual(fig.figures.map((f) => [f.group, f.count]), [['all', 36], ['colour', 24], ['luminance', 12]]);
    const all = fig.figures[0].metrics;
    assert.ok(all.relative_Y_error < 0.024, `relative Y error ${all.relative_Y_error}`);
    assert.ok(all.metrics.NRMSE[1] < 0.016, `NRMSE Y ${all.metrics.NRMSE[1]}`);
    // up the ladder the dominant exposure gets shorter: the darkest cell from the longest (1/15 s),
    // the brightest (3000 cd/m²) from one of the two shortest
    const ladder = fig.regions.filter((r) => r.set === 'luminance').map((r) => r.source);
    assert.deepEqual(fig.regions.filter((r) => r.set === 'luminance').map((r) => r.id), ex.regions.filter((r) => /^E/.test(r.id)).map((r) => r.id));
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
  const rec = T.applyAbsolute(fit.profile, ex.frames, { mode: 'recursive', names: ex.frame_names });
  try {
    const fig = rec.report(test.filter((r) => r.XYZ[1] >= 1), { white: 'E' }).test;
    assert.deepEqual(fig.white, Array.from(T.whiteEqualEnergy(3000)));
    assert.ok(fig.figures[0].metrics.relative_Y_error < 0.024, `Algorithm 1 relative Y error ${fig.figures[0].metrics.relative_Y_error}`);
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
    throwsCode(assert, () => T.fitAbsolute({ inputs: { stimuli: T.readAbsoluteStimuli(ex.stimuli_csv, 's.csv'), bracket: ['a.dng', 'b.dng'], lens_cap: ex.lens_cap_names } },
      { bracket: [ex.frames[0], nikon.frames[1]], lens_cap: ex.lens_cap }), 'FRAME_MISMATCH');
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
    throwsCode(assert, () => T.fitAbsolute(recipeOf(ex, bad), framesOf(ex)), 'NON_MONOTONIC');
    throwsCode(assert, () => T.readAbsoluteStimuli('id,R,G,B\n1,2,3,4\n', 'no-xyz.csv'), 'MISSING_COLUMN');
    throwsCode(assert, () => T.readAbsoluteStimuli('id,R,G,B,X,Y,Z\n1,2,3,4,5,5,5\n', 'no-exposure.csv'), 'MISSING_METADATA');
    // per-patch stimuli with neither S nor frames to measure it from
    throwsCode(assert, () => T.fitAbsolute({ inputs: { stimuli: T.readAbsoluteStimuli(ex.stimuli_csv, 's.csv') } }, {}), 'INVALID_ARGUMENT');
    throwsCode(assert, () => T.applyAbsolute('{"format":"tristim-absolute-profile","version":7}', ex.frames), 'PROFILE_VERSION');
    // the options cross by their field lists: an unknown member or a short exposure is refused, coded
    throwsCode(assert, () => T.applyAbsolute(fit.profile, ex.frames, { names: ex.frame_names, fusion: 'recursive' }), 'INVALID_ARGUMENT');
    throwsCode(assert, () => T.checkAbsoluteSeries(ex.frames, { exposures: ex.frames.map(() => [0.01, 8]) }), 'INVALID_ARGUMENT');
    assert.equal(T.checkAbsoluteSeries(ex.frames, {}).length, 5, 'members left out: their C++ defaults (exposures from the metadata)');
    const maps = T.applyAbsolute(fit.profile, [ex.frames[2]], { mode: 'recursive' });
    try {
      throwsCode(assert, () => maps.report([], { white: 'E', whitepoint: 'D65' }), 'INVALID_ARGUMENT');
      assert.equal(maps.report([], {}).fit.fusion, 'recursive', 'the mode as applied');
    } finally { maps.delete(); }
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
    const fit = T.fitAbsolute(recipeOf(ex, stimuli, { transform: 'T2R' }), framesOf(ex));
    maps = T.applyAbsolute(fit.profile, ex.frames, { names: ex.frame_names });
    // the chart's cells (the chromatic group), white per eq (16)
    const m = maps.report(T.readAbsoluteStimuli(ex.test_csv, 'test.csv'), { white: ex.white_id }).test.figures.find((f) => f.group === 'colour');
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

// ---- one field list: the recipe, its rows and the summaries cross as their JSON ----------------
test('absolute: the recipe and its stimuli cross in the form their JSON has (one field list), strictly', async () => {
  const T = await loadTristim();
  const rows = T.readAbsoluteStimuli('id,set,exposure_s,f_number,iso,file,x,y,w,h,R,G,B,X,Y,Z\n'
    + 'p1,luminance,0.01,8,100,,,,,,10,20,30,5,5,5\nr1,,0,0,0,a.dng,4,6,10,12,,,,2,3,4\n', 'rows.csv');
  // an exposure is [t, N, ISO] and a region [x, y, w, h], as in the recipe's JSON; no member names
  assert.deepEqual(rows[0].exposure, [0.01, 8, 100]);
  assert.deepEqual(rows[1].region, [4, 6, 10, 12]);
  assert.equal(rows[1].file, 'a.dng');
  assert.deepEqual(Object.keys(rows[0]), ['id', 'set', 'exposure', 'file', 'region', 'RGB', 'falloff', 'XYZ']);
  assert.equal(rows[1].x, undefined);
  // the object a JS caller builds is the recipe JSON's inputs/options: the text written from it
  // holds exactly those rows, and reading the text back gives the same object
  const recipe = { inputs: { stimuli: rows, bracket: ['a.dng'] }, options: { w: 12 } };
  const text = T.absoluteRecipeToJson(recipe);
  const doc = JSON.parse(text);
  assert.deepEqual(doc.inputs.stimuli, rows);
  assert.equal(doc.options.w, 12);
  assert.equal(doc.options.fusion, 'weighted');  // left out: the C++ default
  assert.deepEqual(T.absoluteRecipeFromJson(text), { inputs: doc.inputs, options: doc.options });
  assert.deepEqual(T.completeAbsoluteRecipe(recipe).inputs.stimuli, rows);
  // strict: an unknown member (anywhere), a wrong type or an old member name is refused, coded
  throwsCode(assert, () => T.absoluteRecipeToJson({ ...recipe, extra: 1 }), 'RECIPE_INVALID');
  throwsCode(assert, () => T.absoluteRecipeToJson({ ...recipe, options: { zone: 3 } }), 'RECIPE_INVALID');
  throwsCode(assert, () => T.absoluteRecipeToJson({ ...recipe, options: { w: 'wide' } }), 'RECIPE_INVALID');
  throwsCode(assert, () => T.absoluteRecipeToJson({ inputs: { stimuli: [{ ...rows[1], x: 4 }] } }), 'RECIPE_INVALID');
  throwsCode(assert, () => T.absoluteRecipeToJson({ inputs: { stimuli: [{ ...rows[0], exposure: { exposure_s: 0.01 } }] } }), 'RECIPE_INVALID');
  throwsCode(assert, () => T.absoluteRecipeToJson({ inputs: { sensitivities: { choice: 'given', ssf: {} } } }), 'RECIPE_INVALID');
});

// ---- the module's report equals `tristim absolute evaluate --json`, to the bit ----------------
// The fixture (tests/cli/absolute_fixture.cpp) writes the page's example as DNGs named as the page
// names its frames (a black level keeps the read noise below 0 DN, so they decode to the example's
// frames exactly) and the virtual bracket's training chart and scene with stimuli CSVs of region
// rows. The native CLI fits and evaluates the files; the module the same inputs.

const { dir: fixture, cli } = absoluteFixture('tristim-absolute-');
const decode = (dir, names) => names.map((n) => T_.decodeRaw(new Uint8Array(fs.readFileSync(path.join(dir, n)))));
let T_ = null;

test('absolute: the example — the module\'s profile and report equal the CLI\'s on the example\'s files, to the bit', async () => {
  const T = T_ = await loadTristim();
  const dir = path.join(fixture(), 'example');
  cli(dir, ['absolute', 'fit', '--recipe', 'recipe.json', '--out', 'profile.json']);
  const exposures = fs.readFileSync(path.join(dir, 'exposures.txt'), 'utf8').trim().split('\n').flatMap((e) => ['--exposure', e]);
  const white = fs.readFileSync(path.join(dir, 'white_id.txt'), 'utf8').trim();
  const { ex, fit } = await example(T);   // seed 1: the page's example
  assert.equal(white, ex.white_id);
  assert.equal(fit.profile, fs.readFileSync(path.join(dir, 'profile.json'), 'utf8'), 'the profile JSON, byte for byte');
  const expected = JSON.parse(cli(dir, ['absolute', 'evaluate', 'profile.json', '--stimuli', 'test.csv', ...ex.frame_names, ...exposures, '--white', white, '--json']));
  const maps = T.applyAbsolute(fit.profile, ex.frames, { names: ex.frame_names });
  try {
    const report = maps.report(T.readAbsoluteStimuli(fs.readFileSync(path.join(dir, 'test.csv'), 'utf8'), 'test.csv'), { white });
    assert.deepStrictEqual(report, expected);
    assert.equal(report.test.regions.length, 36);
    assert.deepEqual(report.test.figures.map((f) => f.group), ['all', 'colour', 'luminance']);
    // `tristim absolute apply --points`: the maps summary and, per point, the id and the engine's
    // read-out (AbsoluteReadout's list) — the page's summary() and readout(), to the bit
    fs.writeFileSync(path.join(dir, 'points.csv'), 'id,x,y\ncentre,96,96\ncorner,0,191\n');
    const applied = JSON.parse(cli(dir, ['absolute', 'apply', 'profile.json', ...ex.frame_names, ...exposures, '--out', 'xyz.tiff', '--points', 'points.csv']));
    const { out, points, ...summary } = applied;
    assert.equal(out, 'xyz.tiff');
    assert.deepStrictEqual(summary, maps.summary());
    assert.deepStrictEqual(points, [{ id: 'centre', ...maps.readout(96, 96, 5) }, { id: 'corner', ...maps.readout(0, 191, 5) }]);
    assert.equal(points[1].n, 9, 'the 5 x 5 window clipped to 3 x 3 at the corner');
  } finally { maps.delete(); }
});

test('absolute: test scenes of region rows — the module\'s report equals the CLI\'s, to the bit', async () => {
  const T = T_ = await loadTristim();
  const dir = fixture();
  const scenes = [1, 2, 3, 4, 5].map((i) => `scene_${i}.dng`), trains = [1, 2, 3, 4, 5].map((i) => `train_${i}.dng`);
  const caps = ['cap_1.dng', 'cap_2.dng'];
  const stimuli = T.readAbsoluteStimuli(fs.readFileSync(path.join(dir, 'stimuli.csv'), 'utf8'), 'stimuli.csv');
  const flags = ['--stimuli', 'stimuli.csv', '--dark', caps[0], '--dark', caps[1], '--flat', 'flat.dng', '--camera', 'Canon_EOS_5D_Mark_II'];
  const frames = { scene: decode(dir, scenes), train: decode(dir, trains), caps: decode(dir, caps), flat: decode(dir, ['flat.dng'])[0] };
  const read = (name) => T.readAbsoluteStimuli(fs.readFileSync(path.join(dir, name), 'utf8'), name);
  try {
    for (const [bracket, handles, others, test] of [
      [scenes, frames.scene, { other_names: trains, others: frames.train }, 'scene_test.csv'],   // training photos apart from the scene
      [trains, frames.train, {}, 'train_test.csv'],                                               // region rows naming the bracket (the page's case)
    ]) {
      const recipe = { inputs: { stimuli, bracket, lens_cap: caps, flat: 'flat.dng', sensitivities: { choice: 'camera', camera: 'Canon_EOS_5D_Mark_II' } } };
      const fit = T.fitAbsolute(recipe, { bracket: handles, lens_cap: frames.caps, flat: frames.flat, ...others });
      cli(dir, ['absolute', 'fit', ...flags, ...bracket.flatMap((b) => ['--bracket', b]), '--out', 'p43.json']);
      assert.equal(fit.profile, fs.readFileSync(path.join(dir, 'p43.json'), 'utf8'), `${test}: the profile JSON, byte for byte`);
      const expected = JSON.parse(cli(dir, ['absolute', 'evaluate', 'p43.json', '--stimuli', test, ...bracket, '--json']));
      const maps = T.applyAbsolute(fit.profile, handles, { names: bracket });
      try {
        const report = maps.report(read(test));
        assert.deepStrictEqual(report, expected, test);
        assert.ok(report.test.regions.length >= 24, `${test}: ${report.test.regions.length} regions`);
        assert.equal(report.test.white_rule, 'eq16');
      } finally { maps.delete(); }
    }
    // a test scene whose region names a file outside the bracket, or lies outside the frame
    const maps = T.applyAbsolute(T.fitAbsolute({ inputs: { stimuli, bracket: trains, lens_cap: caps, flat: 'flat.dng' } },
      { bracket: frames.train, lens_cap: frames.caps, flat: frames.flat }).profile, frames.train, { names: trains });
    try {
      throwsCode(assert, () => maps.report(T.readAbsoluteStimuli('id,file,x,y,w,h,X,Y,Z\nA1,scene_3.dng,4,4,8,8,1,1,1\n', 't.csv')), 'UNKNOWN_ID');
      throwsCode(assert, () => maps.report(T.readAbsoluteStimuli('id,file,x,y,w,h,X,Y,Z\nA1,train_3.dng,124,4,8,8,1,1,1\n', 't.csv')), 'INVALID_ARGUMENT');
    } finally { maps.delete(); }
  } finally {
    for (const f of [...frames.scene, ...frames.train, ...frames.caps, frames.flat]) f.delete();
  }
});

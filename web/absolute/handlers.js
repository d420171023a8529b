// Worker handlers of the Absolute mode (Guarnera, Bianco & Schettini 2018): a bracketed series of
// RAWs, lens-cap frames and a flat decoded here (state.abs), the training and test stimuli CSVs
// read by the engine (per-patch rows, and region rows naming files of the series), the absolute
// recipe fitted (fitAbsolute) and the profile applied to the series (the AbsoluteMaps handle stays
// here), the engine's report on the test scene (the one `tristim absolute evaluate` prints),
// renders of the luminance and source-exposure maps and read-outs. The example comes from the
// engine's virtual bracket camera.
import { reply, coded } from '../lib/reply.js';
import { renderLuminance, renderSource } from './render.js';
import { handlers as sensitivities, chosenSensitivities } from './sensitivities_handlers.js';

const free = (...hs) => { for (const h of hs.flat()) h?.delete?.(); };

function abs(state) {
  state.abs ??= {};
  state.abs.series ??= [];
  state.abs.names ??= [];
  state.abs.lensCap ??= [];
  state.abs.capNames ??= [];
  return state.abs;
}

function describe(raw, name) {
  const m = raw.metadata();
  return { name, make: m.make, model: m.model, width: raw.width(), height: raw.height(), exposure_s: m.shutter_s, f_number: m.f_number, iso: m.iso };
}

function decodeAll(T, files, progress, what) {
  const out = [];
  try {
    files.forEach((f, i) => {
      progress(i / files.length, `decoding ${what} ${i + 1} of ${files.length}`);
      try { out.push(T.decodeRaw(new Uint8Array(f.bytes))); } catch (e) { throw Object.assign(new Error(`'${f.name}': ${e.message}`), { code: e.code }); }
    });
  } catch (e) { free(out); throw e; }
  return out;
}

function clearResults(a) {
  free(a.maps);
  a.maps = null; a.xyz = null; a.source = null;
}

/// The series with its exposures checked by the engine (same camera and size; t, N from the
/// metadata unless given). Returns one row per frame.
function checkSeries(T, a, exposures) {
  const got = T.checkAbsoluteSeries(a.series, { exposures: exposures ?? [], names: a.names });
  return a.series.map((r, i) => ({ ...describe(r, a.names[i]), exposure: got[i] }));
}

export const handlers = {
  ...sensitivities,
  /// Decodes a bracketed series (several RAWs of one scene). Errors name the file: RAW decoding
  /// codes, FRAME_MISMATCH (another camera or size), MISSING_METADATA (no t or N: the rows are
  /// still returned so the page can ask for them, with `missing` set).
  absSeries: (T, { files }, { state, progress }) => {
    const a = abs(state);
    const list = decodeAll(T, files, progress, 'frame');
    free(a.series); clearResults(a);
    a.series = list; a.names = files.map((f) => f.name);
    const rows = a.series.map((r, i) => describe(r, a.names[i]));
    try {
      return { result: { frames: checkSeries(T, a) } };
    } catch (e) {
      if (e.code !== 'MISSING_METADATA') { free(a.series); a.series = []; a.names = []; throw e; }
      return { result: { frames: rows, missing: { code: e.code, message: e.message } } };
    }
  },

  /// Re-checks the series with exposures typed in by the user ([[t, N, ISO], …], zeros: from the
  /// metadata).
  absExposures: (T, { exposures }, { state }) => ({ result: { frames: checkSeries(T, abs(state), exposures) } }),

  /// Lens-cap frames (kind 'lensCap', several) or a flat field (kind 'flat', one).
  absCalibration: (T, { kind, files }, { state, progress }) => {
    const a = abs(state);
    const list = files.length ? decodeAll(T, files, progress, kind === 'flat' ? 'flat field' : 'lens-cap frame') : [];
    if (kind === 'flat') { free(a.flat); a.flat = list[0] ?? null; a.flatName = files[0]?.name ?? ''; free(list.slice(1)); } else { free(a.lensCap); a.lensCap = list; a.capNames = files.map((f) => f.name); }
    return { result: { frames: list.map((r, i) => describe(r, files[i].name)) } };
  },

  /// Reads a stimuli CSV (the engine's reader): the training stimuli (kind 'training') or a test
  /// scene (kind 'test'); keeps the rows. Region rows name files of the series.
  absStimuli: (T, { text, name, kind = 'training' }, { state }) => {
    const a = abs(state);
    const rows = T.readAbsoluteStimuli(text, name);
    if (kind === 'test') a.test = rows; else a.stimuli = rows;
    const exposures = new Set(rows.filter((r) => !r.file).map((r) => r.exposure.join('/')));  // [t, N, ISO]
    return { result: { count: rows.length, luminance: rows.filter((r) => r.set === 'luminance').length, colour: rows.filter((r) => r.set === 'colour').length,
      exposures: exposures.size, regionRows: rows.filter((r) => r.file).length, files: [...new Set(rows.filter((r) => r.file).map((r) => r.file))],
      ids: rows.map((r) => r.id), colourIds: rows.filter((r) => r.set === 'colour').map((r) => r.id),
      regions: rows.filter((r) => r.file).map(({ id, region: [x, y, w, h] }) => ({ id, x, y, w, h })) } };
  },

  /// Forgets the test scene.
  absClearTest: (T, _msg, { state }) => { abs(state).test = null; return { result: true }; },

  /// The virtual-camera example: the series, lens cap, flat, training stimuli and test scene (the
  /// cells as region rows with their known X, Y, Z) take the place of loaded files.
  absExample: (T, { options = {} }, { state, progress }) => {
    const a = abs(state);
    progress(NaN, 'generating the bracketed series with the virtual camera');
    const ex = T.absoluteExample(options);
    free(a.series, a.lensCap, a.flat); clearResults(a);
    a.series = ex.frames; a.lensCap = ex.lens_cap; a.flat = ex.flat;
    a.names = ex.frame_names; a.capNames = ex.lens_cap_names; a.flatName = ex.flat_name;
    return reply({
      frames: checkSeries(T, a), lensCap: a.lensCap.map((r, i) => describe(r, a.capNames[i])),
      flat: describe(a.flat, a.flatName), stimuliCsv: ex.stimuli_csv, testCsv: ex.test_csv, camera: ex.camera, whiteId: ex.white_id,
    });
  },

  /// Fits the absolute recipe: the stimuli (per patch, or regions of the series' files) + lens cap
  /// (n) + flat (f(r)) + the series (S measured), the page's options. Returns the completed recipe,
  /// the profile JSON, the OECF panels (fig 5) and the report (fit and training figures).
  absFit: (T, { options }, { state, progress }) => {
    const a = abs(state);
    if (!a.stimuli) throw coded('load the training stimuli first', 'NO_STIMULI');
    progress(NaN, 'fitting eq (8) per channel across every exposure, then the colour matrix');
    // The sensitivities for A_R, A_G, A_B: an uploaded CSV or an estimate kept here, else a built-in camera.
    const { sensitivities, camera, ...rest } = options;
    const given = chosenSensitivities(state, sensitivities);
    // The recipe's form of given curves (its JSON): wavelengths and one array per channel R, G, B.
    const curves = (ssf) => ({ wavelengths: ssf.wavelengths, R: ssf.values[0], G: ssf.values[1], B: ssf.values[2] });
    const choice = given ? { choice: 'given', ...curves(given.ssf), source: given.source } : camera ? { choice: 'camera', camera } : { choice: 'none' };
    const recipe = { inputs: { stimuli: a.stimuli, bracket: a.names, lens_cap: a.capNames, flat: a.flat ? a.flatName : '', sensitivities: choice }, options: rest };
    const fit = T.fitAbsolute(recipe, { bracket: a.series, lens_cap: a.lensCap, flat: a.flat });
    a.fit = fit;
    clearResults(a);
    return reply({ ...fit, recipeJson: T.absoluteRecipeToJson(fit.recipe) });
  },

  /// Applies the fitted profile to the series; the engine's report on the test scene (white: an id
  /// of the scene's, 'E', or '' for the engine's choice); renders the maps.
  absApply: (T, { mode, exposures, white = '', render }, { state, progress }) => {
    const a = abs(state);
    if (!a.fit) throw coded('fit a profile first', 'NO_PROFILE');
    if (!a.series.length) throw coded('load a bracketed series first', 'NO_IMAGE');
    clearResults(a);
    const t0 = performance.now();
    a.maps = T.applyAbsolute(a.fit.profile, a.series, { mode, exposures: exposures ?? [], names: a.names },
      (fraction, stage) => progress(0.8 * fraction, stage));
    const ms = performance.now() - t0;
    progress(0.85, 'measuring the test scene');
    const report = a.maps.report(a.test ?? [], { white });
    a.summary = report.maps;
    a.xyz = a.maps.XYZ();
    a.source = a.maps.source();
    progress(0.9, 'rendering');
    return reply({ report, ms, ...renderAll(a, render) });
  },

  /// Re-renders the kept maps (colour map, log scale).
  absRender: (T, { render }, { state }) => {
    const a = abs(state);
    if (!a.xyz) throw coded('no maps yet', 'NO_IMAGE');
    return reply(renderAll(a, render));
  },

  /// The X, Y, Z map as a 32-bit float TIFF (cd/m², NaN where every exposure clipped), the bytes
  /// `tristim absolute apply --out` writes.
  absMapTiff: (T, _msg, { state }) => {
    const a = abs(state);
    if (!a.maps) throw coded('no maps yet', 'NO_IMAGE');
    return reply({ bytes: a.maps.tiff() });
  },

  /// X, Y, Z (mean over a window), L(R, G, B) and the source exposure at a pixel; the test scene's
  /// region under it, with its reference X, Y, Z.
  absReadout: (T, { x, y, window = 5 }, { state }) => {
    const a = abs(state);
    if (!a.maps) throw coded('no maps yet', 'NO_IMAGE');
    const { width, height } = a.summary;
    if (!(x >= 0 && y >= 0 && x < width && y < height)) return { result: null };
    const r = a.maps.readout(Math.floor(x), Math.floor(y), window);
    const region = a.test?.find(({ file, region: [gx, gy, gw, gh] = [] }) => file && x >= gx && x < gx + gw && y >= gy && y < gy + gh);
    // AbsoluteReadout by its field list (a figure that is not a number is null): NaN again for the view
    const nan = (v) => v.map((c) => c ?? NaN);
    return { result: { ...r, XYZ: nan(r.XYZ), L: nan(r.L), region: region ? { id: region.id, XYZ: Array.from(region.XYZ) } : null } };
  },
};

function renderAll(a, { lut, log = true, maxSide = 900, sourceColours } = {}) {
  const { width, height } = a.summary;
  const lum = renderLuminance(a.xyz, width, height, { lut: new Uint8Array(lut), log, maxSide, low: a.summary.Y_p01, high: a.summary.Y.max });
  const src = renderSource(a.source, width, height, { colours: sourceColours, maxSide });
  return { luminance: lum, source: src };
}

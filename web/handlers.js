// Worker request handlers, by request type: (T, msg, {state, progress}) -> {result, transfer}.
// T is the wasm module; handlers stay thin: they call the engine (whose results own their typed
// arrays) and list the buffers for transfer. Decoded images stay here (state.raw[slot]).
import { renderXYZ, encodingTable } from './lib/render.js';

/// Buffers of every typed array found in a (nested) plain object.
function buffers(obj, out = []) {
  if (ArrayBuffer.isView(obj)) out.push(obj.buffer);
  else if (obj && typeof obj === 'object') for (const v of Object.values(obj)) buffers(v, out);
  return [...new Set(out)];
}
const reply = (result) => ({ result, transfer: buffers(result) });
const noImage = (what) => Object.assign(new Error(`no RAW image decoded ${what}`), { code: 'NO_IMAGE' });

/// Sets the chart image's dark frame and flat field from the decoded slots (Abed 2013 App. C);
/// returns what the engine reports. Throws (e.g. FRAME_MISMATCH) when a frame does not fit.
function calibrate(state) {
  const chart = state.raw?.chart;
  if (!chart) return null;
  const out = {};
  if (state.raw.dark) out.dark = chart.setDark(state.raw.dark, state.darkMode ?? 'pixel'); else chart.clearDark();
  if (state.raw.flat) {
    out.flat = chart.setFlat(state.raw.flat, state.flatMode ?? 'pixel');
    out.flat.mode = state.flatMode ?? 'pixel';
  } else chart.clearFlat();
  return out;
}
function calibrateQuietly(state) {
  try { return calibrate(state); } catch { state.raw?.chart?.clearDark(); state.raw?.chart?.clearFlat(); return null; }
}
function freeRaw(raw) {
  if (raw) for (const r of [raw].flat()) r.delete();
}

/// L*a*b* of reference and estimate and display sRGB of the estimate, from the engine (CIE 15
/// Lab; Bradford to D65 + sRGB for display), for the Lab planes and swatches of the results.
function displayOf(T, refXYZ, estXYZ, white) {
  const ref = Float64Array.from(refXYZ), est = Float64Array.from(estXYZ);
  return { white: Array.from(white), refLab: T.XYZToLab(ref, white), estLab: T.XYZToLab(est, white), estSRGB: T.XYZToDisplaySRGB(est, white) };
}

export const handlers = {
  hello: (T) => ({ result: { version: T.version() } }),

  /// Every table the page builds its pickers from.
  catalog: (T) => {
    const layouts = Object.fromEntries(T.listChartLayouts().map((id) => [id, id === 'custom' ? null : T.chartLayout({ chart: id })]));
    return reply({ charts: T.listCharts(), illuminants: T.listIlluminants(), models: T.listModels(), objectives: T.listObjectives(),
      linearisations: T.listLinearisations(), surfaces: T.listSurfaceCorrections(), cameras: T.listCameras(), layouts });
  },

  reference: (T, { chart, illuminant, observer }) => reply(T.referenceChart(chart, illuminant, observer)),
  /// A reference file, with the digest a recipe records for it.
  parseReference: (T, { text, fileName, illuminant, observer }) =>
    reply({ ...T.parseReferenceFile(text, fileName, illuminant, observer), data_digest: T.bytesDigest(text) }),
  spectralLocus: (T, { observer }) => reply(T.spectralLocus(observer)),

  /// Decodes RAW bytes into state.raw[slot] ('chart', 'dark', 'flat', 'scene'); returns metadata,
  /// the display preview (chart and scene) and, for dark/flat, the calibration it gave the chart.
  /// `bytesList` (dark frames): several files, decoded and averaged by the engine (setDark).
  decode: (T, { slot = 'chart', bytes, bytesList, flatMode, previewSide = 1200 }, { state, progress }) => {
    progress(NaN, 'decoding RAW');
    state.raw ??= {};
    let raw;
    if (bytesList) {
      const list = [];
      try {
        bytesList.forEach((b, i) => {
          progress(i / bytesList.length, `decoding frame ${i + 1} of ${bytesList.length}`);
          list.push(T.decodeRaw(new Uint8Array(b)));
        });
      } catch (e) { for (const r of list) r.delete(); throw e; }
      raw = list;
    } else raw = T.decodeRaw(new Uint8Array(bytes));
    const first = Array.isArray(raw) ? raw[0] : raw;
    progress(0.8, 'building preview');
    let result;
    try {
      result = { width: first.width(), height: first.height(), metadata: first.metadata() };
      if (slot === 'chart') {
        const p = first.preview(previewSide);
        result.preview = { ...p, rgba: new Uint8ClampedArray(p.rgba.buffer) };
      }
    } catch (e) { freeRaw(raw); throw e; }
    // The new image replaces the slot's previous one only once it fits (calibrate below).
    const previous = { raw: state.raw[slot], flatMode: state.flatMode };
    state.raw[slot] = raw;
    if (slot === 'flat') state.flatMode = flatMode;
    if (slot !== 'scene') {
      try {
        result.calibration = calibrate(state);
      } catch (e) {
        // A frame that does not fit (FRAME_MISMATCH, FLAT_FIELD_ZERO, ...) is refused: the slot
        // keeps its previous image, and the calibration that went with it.
        freeRaw(raw);
        if (previous.raw) state.raw[slot] = previous.raw; else delete state.raw[slot];
        state.flatMode = previous.flatMode;
        calibrateQuietly(state);
        throw e;
      }
    }
    freeRaw(previous.raw);
    return reply(result);
  },

  /// A measured patch file (CSV/CGATS with R,G,B and maybe X,Y,Z) for a held-out test set.
  parsePatchFile: (T, { text, fileName }) => reply(T.parsePatchFile(text, fileName)),

  sample: (T, { layout, corners, sampleOptions = {} }, { state }) => {
    if (!state.raw?.chart) throw noImage('yet');
    return reply(T.sampleChart(state.raw.chart, layout, corners, sampleOptions));
  },
  /// The patch grid of a layout placed by four corners (for drawing; the engine's homography).
  grid: (T, { layout, corners }) => reply({ layout: T.chartLayout(layout), homography: T.homographyUnitSquare(corners) }),

  forget: (T, { slot }, { state }) => {
    freeRaw(state.raw?.[slot]);
    delete state.raw?.[slot];
    return { result: calibrateQuietly(state) };
  },

  /// Fits a recipe on the chart sample paired with the reference (and evaluates the profile on
  /// the held-out set {name, ids, rgb, xyz} when there is one).
  fit: (T, { recipe, sample, reference, heldOut }, { progress }) => {
    progress(NaN, `fitting ${recipe.characterisation.model}`);
    if (heldOut) recipe.evaluation.held_out_digest = T.trainingDigest(heldOut.ids, heldOut.rgb, heldOut.xyz);
    const out = T.fitSample(recipe, sample, reference);
    out.display = displayOf(T, out.reference_XYZ, out.evaluation.fit.fitted, out.recipe.characterisation.lab_white);
    if (heldOut) out.held_out = { ...T.evaluateProfile(out.profile, heldOut.rgb, heldOut.xyz, heldOut.ids).metrics, set: heldOut.name };
    return reply(out);
  },

  evaluate: (T, { profile, rgb, xyz, ids }) => {
    const out = T.evaluateProfile(profile, rgb, xyz, ids);
    out.display = displayOf(T, xyz, out.estimated, out.profile.white);
    return reply(out);
  },

  /// Applies a profile to a decoded RAW, keeps the XYZ image here and returns display renders.
  applyRender: (T, { profile, slot = 'chart', white, lut, maxSide }, { state, progress }) => {
    const raw = state.raw?.[slot];
    if (!raw) throw noImage('for this step yet');
    progress(NaN, 'applying the profile');
    const t0 = performance.now();
    const img = T.applyProfile(profile, raw);
    const tApply = performance.now() - t0;
    progress(0.7, 'rendering');
    state.xyz = { ...img, white };
    const r = renderXYZ(img.pixels, img.width, img.height,
      { matrix: T.displayMatrix(white), enc: encodingTable(T, white), lut: new Uint8Array(lut), maxSide });
    return reply({ ...r, fullWidth: img.width, fullHeight: img.height, msApply: tApply, msRender: performance.now() - t0 - tApply });
  },

  /// X, Y, Z, x, y and L*a*b* of one pixel of the last applied image.
  pixel: (T, { x, y }, { state }) => {
    const img = state.xyz;
    if (!img) throw Object.assign(new Error('no applied image'), { code: 'NO_IMAGE' });
    const i = Math.floor(y) * img.width + Math.floor(x);
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return { result: null };
    const XYZ = [img.pixels[3 * i], img.pixels[3 * i + 1], img.pixels[3 * i + 2]];
    const s = XYZ[0] + XYZ[1] + XYZ[2];
    return { result: { XYZ, xy: s > 0 ? [XYZ[0] / s, XYZ[1] / s] : [NaN, NaN], Lab: Array.from(T.XYZToLab(XYZ, img.white)) } };
  },

  exportIcc: (T, { profile }) => reply({ bytes: T.exportIcc(profile) }),
  patchCsv: (T, { ids, rgb, xyz, estimated, white, loo }) => ({ result: { text: T.patchCsv(ids, rgb, xyz, estimated, white, loo) } }),
  exportCube: (T, { profile, size = 33 }) => ({ result: { text: T.exportCube(profile, size) } }),
};

// Worker request handlers, by request type: (T, msg, {state, progress}) -> {result, transfer}.
// T is the wasm module; handlers stay thin: they call the engine, copy arrays out of the wasm
// heap and list them for transfer. Decoded images stay here (state.raw[slot]).
import { renderXYZ, encodingTable } from './lib/render.js';
import { plain, referenceOut, sampleOut, fitOut, evaluationOut } from './lib/shapes.js';

const ENGINE_FUNCTIONS = ['listCharts', 'listIlluminants', 'listCameras', 'referenceChart', 'parseReferenceFile',
  'spectralLocus', 'decodeRaw', 'sampleChart', 'listModels', 'listObjectives', 'fitModel', 'evaluateProfile',
  'applyProfileToImage', 'exportIcc', 'exportCube', 'exportPatchCsv', 'listChartLayouts', 'parsePatchFile'];

function need(T, fn) {
  if (typeof T[fn] !== 'function') {
    throw Object.assign(new Error(`this build of the colour engine has no ${fn}()`), { code: 'NOT_AVAILABLE' });
  }
  return T[fn];
}

/// Buffers of every typed array found in a (shallow or nested) plain object.
function buffers(obj, out = []) {
  if (ArrayBuffer.isView(obj)) out.push(obj.buffer);
  else if (obj && typeof obj === 'object') for (const v of Object.values(obj)) buffers(v, out);
  return [...new Set(out)];
}
const reply = (result) => ({ result, transfer: buffers(result) });

/// Sets the chart image's dark frame and flat field from the decoded slots (Abed 2013 App. C);
/// returns what the engine reports. Throws (e.g. FRAME_MISMATCH) when a frame does not fit.
function calibrate(state) {
  const chart = state.raw?.chart;
  if (!chart || typeof chart.setDark !== 'function') return null;
  const out = {};
  if (state.raw.dark) out.dark = plain(chart.setDark(state.raw.dark)); else chart.clearDark();
  if (state.raw.flat) out.flat = plain(chart.setFlat(state.raw.flat, state.flatOptions ?? {})); else chart.clearFlat();
  return out;
}
/// The profile applied to the decoded image's linear camera RGB (dark/flat applied) -> XYZ.
function applyImage(T, profile, raw) {
  const width = raw.width(), height = raw.height();
  const rgb = raw.linearRGB();
  const XYZ = need(T, 'applyProfileToImage')(profile, rgb, width, height);
  return { width, height, XYZ: XYZ instanceof Float32Array ? XYZ : Float32Array.from(XYZ) };
}
function calibrateQuietly(state) {
  try { return calibrate(state); } catch { state.raw?.chart?.clearDark?.(); state.raw?.chart?.clearFlat?.(); return null; }
}

function freeRaw(raw) {
  if (raw) for (const r of [raw].flat()) r.delete();
}
function dropRaw(state, slot) {
  freeRaw(state.raw?.[slot]);
  delete state.raw?.[slot];
}

/// L*a*b* of reference and estimate and display sRGB of the estimate, from the engine (CIE 15
/// Lab; Bradford to D65 + sRGB for display), for the Lab planes and swatches of the results.
function displayOf(T, refXYZ, estXYZ, white) {
  if (!white || !estXYZ) return null;
  const ref = Float64Array.from(refXYZ), est = Float64Array.from(estXYZ);
  return { white: Array.from(white), refLab: T.XYZToLab(ref, white), estLab: T.XYZToLab(est, white), estSRGB: T.XYZToDisplaySRGB(est, white) };
}

export const handlers = {
  hello: (T) => ({ result: { version: T.version() } }),

  capabilities: (T) => ({
    result: Object.fromEntries(ENGINE_FUNCTIONS.map((f) => [f, typeof T[f] === 'function'])),
  }),

  catalog: (T) => {
    const list = (fn) => (typeof T[fn] === 'function' ? T[fn]() : null);
    return { result: { charts: list('listCharts'), illuminants: list('listIlluminants'), models: list('listModels'),
      objectives: list('listObjectives'), cameras: list('listCameras') } };
  },

  reference: (T, { chart, illuminant, observer }) =>
    reply(referenceOut(need(T, 'referenceChart')(chart, illuminant, observer))),

  parseReference: (T, { text, fileName, illuminant, observer }) =>
    reply(referenceOut(need(T, 'parseReferenceFile')(text, fileName, illuminant, observer))),

  spectralLocus: (T, { observer }) => {
    const l = need(T, 'spectralLocus')(observer);
    return reply({ wavelengths: Float64Array.from(l.wavelengths), x: Float64Array.from(l.x), y: Float64Array.from(l.y) });
  },

  /// Decodes RAW bytes into state.raw[slot] ('chart', 'dark', 'flat', 'scene'); returns metadata,
  /// the display preview (chart and scene) and, for dark/flat, the calibration it gave the chart.
  /// `bytesList` (dark frames): several files, decoded and averaged by the engine (setDark).
  decode: (T, { slot = 'chart', bytes, bytesList, flatOptions, previewSide = 1200 }, { state, progress }) => {
    const decodeRaw = need(T, 'decodeRaw');
    progress(NaN, 'decoding RAW');
    state.raw ??= {};
    let raw;
    if (bytesList) {
      const list = [];
      try {
        bytesList.forEach((b, i) => {
          progress(i / bytesList.length, `decoding frame ${i + 1} of ${bytesList.length}`);
          list.push(decodeRaw(new Uint8Array(b)));
        });
      } catch (e) { for (const r of list) r.delete(); throw e; }
      raw = list;
    } else raw = decodeRaw(new Uint8Array(bytes));
    const first = Array.isArray(raw) ? raw[0] : raw;
    progress(0.8, 'building preview');
    let result;
    try {
      const meta = typeof first.metadata === 'function' ? first.metadata() : {};
      const metadata = typeof meta === 'string' ? JSON.parse(meta) : plain(meta);
      result = { width: first.width(), height: first.height(), metadata };
      if (slot === 'chart' && typeof first.preview === 'function') {
        const p = first.preview(previewSide);
        result.preview = { width: p.width, height: p.height, scale: p.scale, rgba: new Uint8ClampedArray(p.rgba.slice().buffer) };
      }
    } catch (e) { freeRaw(raw); throw e; }
    // The new image replaces the slot's previous one only once it fits (calibrate below).
    const previous = { raw: state.raw[slot], flatOptions: state.flatOptions };
    state.raw[slot] = raw;
    if (slot === 'flat') state.flatOptions = flatOptions;
    if (slot !== 'scene') {
      try {
        result.calibration = calibrate(state);
      } catch (e) {
        // A frame that does not fit (FRAME_MISMATCH, FLAT_FIELD_ZERO, ...) is refused: the slot
        // keeps its previous image, and the calibration that went with it.
        freeRaw(raw);
        if (previous.raw) state.raw[slot] = previous.raw; else delete state.raw[slot];
        state.flatOptions = previous.flatOptions;
        calibrateQuietly(state);
        throw e;
      }
    }
    freeRaw(previous.raw);
    return reply(result);
  },

  /// A measured patch file (CSV/CGATS with R,G,B and maybe X,Y,Z) for a held-out test set.
  parsePatchFile: (T, { text, fileName }) => reply(plain(need(T, 'parsePatchFile')(text, fileName))),

  sample: (T, { layout, corners, sampleOptions = {} }, { state }) => {
    const raw = state.raw?.chart;
    if (!raw) throw Object.assign(new Error('no RAW image decoded yet'), { code: 'NO_IMAGE' });
    const out = need(T, 'sampleChart')(raw, layout, Float64Array.from(corners), sampleOptions);
    return reply(sampleOut(out));
  },

  forget: (T, { slot }, { state }) => { dropRaw(state, slot); return { result: calibrateQuietly(state) }; },

  fit: (T, { rgb, xyz, ids, options }, { progress }) => {
    progress(NaN, `fitting ${options.model}`);
    const out = fitOut(need(T, 'fitModel')(Float64Array.from(rgb), Float64Array.from(xyz), ids, options));
    out.display = displayOf(T, xyz, out.fitted, options.white);
    return reply(out);
  },

  evaluate: (T, { profile, rgb, xyz, ids }) => {
    const out = evaluationOut(need(T, 'evaluateProfile')(profile, Float64Array.from(rgb), Float64Array.from(xyz), ids));
    out.display = displayOf(T, xyz, out.estimated, out.white);
    return reply(out);
  },

  /// Applies a profile to a decoded RAW, keeps the XYZ image here and returns display renders.
  applyRender: (T, { profile, slot = 'chart', white, lut, maxSide }, { state, progress }) => {
    const raw = state.raw?.[slot];
    if (!raw) throw Object.assign(new Error('no RAW image decoded for this step yet'), { code: 'NO_IMAGE' });
    progress(NaN, 'applying the profile');
    const t0 = performance.now();
    const img = applyImage(T, profile, raw);
    const tApply = performance.now() - t0;
    progress(0.7, 'rendering');
    state.xyz = { ...img, white };
    const r = renderXYZ(img.XYZ, img.width, img.height,
      { matrix: T.displayMatrix(white), enc: encodingTable(T, white), lut: new Uint8Array(lut), maxSide });
    return reply({ ...r, fullWidth: img.width, fullHeight: img.height, msApply: tApply, msRender: performance.now() - t0 - tApply });
  },

  /// X, Y, Z, x, y and L*a*b* of one pixel of the last applied image.
  pixel: (T, { x, y }, { state }) => {
    const img = state.xyz;
    if (!img) throw Object.assign(new Error('no applied image'), { code: 'NO_IMAGE' });
    const i = Math.floor(y) * img.width + Math.floor(x);
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return { result: null };
    const XYZ = [img.XYZ[3 * i], img.XYZ[3 * i + 1], img.XYZ[3 * i + 2]];
    const s = XYZ[0] + XYZ[1] + XYZ[2];
    return { result: { XYZ, xy: s > 0 ? [XYZ[0] / s, XYZ[1] / s] : [NaN, NaN], Lab: Array.from(T.XYZToLab(Float64Array.from(XYZ), img.white)) } };
  },

  exportIcc: (T, { profile }) => reply({ bytes: Uint8Array.from(need(T, 'exportIcc')(profile)) }),
  exportPatchCsv: (T, { profile, rgb, xyz, ids }) => ({ result: { text: need(T, 'exportPatchCsv')(profile, Float64Array.from(rgb), Float64Array.from(xyz), ids) } }),
  exportCube: (T, { profile, size = 33 }) => ({ result: { text: need(T, 'exportCube')(profile, size) } }),
};

// Worker handlers of step 2: decoding RAW files into the worker's slots ('chart', 'dark', 'flat',
// 'scene', and 'chart2', 'chart3', … — extra chart images, issue 48, each with its own 'dark<k>',
// 'flat<k>'; the images stay here, state.raw[slot]), each chart image's dark/flat calibration,
// sampling the chart, the engine's patch grid for the corner editor.
import { reply, coded } from '../lib/reply.js';

/// A slot's role and number: 'chart' / 'dark' / 'flat' (k ''), 'chart3' / 'dark3' / 'flat3' (k '3').
const parse = (slot) => /^(chart|dark|flat)(\d*)$/.exec(slot ?? '') ?? [];
/// The chart slot a slot calibrates (undefined: none, e.g. 'scene').
const targetOf = (slot) => { const [, role, k] = parse(slot); return role ? `chart${k}` : undefined; };
/// Each chart slot's frame slots and flat-field mode.
const framesOf = (target) => { const k = parse(target)[2] ?? ''; return { dark: `dark${k}`, flat: `flat${k}`, mode: `flatMode${k}` }; };
const isChart = (slot) => parse(slot)[1] === 'chart';
/// Sets a chart image's dark frame and flat field from its decoded frame slots (Abed 2013 App. C);
/// returns what the engine reports. Throws (e.g. FRAME_MISMATCH) when a frame does not fit.
function calibrate(state, target = 'chart') {
  const chart = state.raw?.[target], f = framesOf(target);
  if (!chart) return null;
  const out = {};
  if (state.raw[f.dark]) out.dark = chart.setDark(state.raw[f.dark], 'per_pixel'); else chart.clearDark();
  if (state.raw[f.flat]) {
    out.flat = chart.setFlat(state.raw[f.flat], state[f.mode] ?? 'pixel');
    out.flat.mode = state[f.mode] ?? 'pixel';
  } else chart.clearFlat();
  return out;
}
function calibrateQuietly(state, target = 'chart') {
  try { return calibrate(state, target); } catch { state.raw?.[target]?.clearDark(); state.raw?.[target]?.clearFlat(); return null; }
}
const previewOf = (image, side) => {
  const p = image.preview(side);
  return { ...p, rgba: new Uint8ClampedArray(p.rgba.buffer) };
};
function freeRaw(raw) {
  if (raw) for (const r of [raw].flat()) r.delete();
}

export { isChart };

export const handlers = {
  /// Decodes RAW bytes into state.raw[slot] ('chart', 'dark', 'flat', 'scene'); returns metadata,
  /// the display preview (chart; previewSide 0: none, ask 'preview' later) and, for dark/flat,
  /// the calibration it gave the chart.
  /// `bytesList` (dark frames): several files, decoded and averaged by the engine (setDark).
  /// `url` instead of bytes: a file of the site fetched by the worker (the example, web/boot.js:
  /// its decode does not wait for the page's main thread).
  decode: async (T, { slot = 'chart', bytes, bytesList, url, response, flatMode, previewSide = 1200 }, { state, progress }) => {
    if (url) {
      const res = await (response ?? fetch(url));   // worker.js started the download on arrival
      if (!res.ok) throw coded(`${url}: HTTP ${res.status}`, 'EXAMPLE_MISSING');
      bytes = await res.arrayBuffer();
    }
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
      if (isChart(slot) && previewSide > 0) result.preview = previewOf(first, previewSide);
    } catch (e) { freeRaw(raw); throw e; }
    // The new image replaces the slot's previous one only once it fits (calibrate below).
    const target = targetOf(slot), mode = target && framesOf(target).mode;
    const previous = { raw: state.raw[slot], flatMode: mode && state[mode] };
    state.raw[slot] = raw;
    if (parse(slot)[1] === 'flat') state[mode] = flatMode;
    if (target) {
      try {
        result.calibration = calibrate(state, target);
      } catch (e) {
        // A frame that does not fit (FRAME_MISMATCH, FLAT_FIELD_ZERO, ...) is refused: the slot
        // keeps its previous image, and the calibration that went with it.
        freeRaw(raw);
        if (previous.raw) state.raw[slot] = previous.raw; else delete state.raw[slot];
        state[mode] = previous.flatMode;
        calibrateQuietly(state, target);
        throw e;
      }
    }
    freeRaw(previous.raw);
    return reply(result);
  },

  /// The display preview of the image in a slot (its first frame), or null when there is none.
  preview: (T, { slot = 'chart', previewSide = 1200 }, { state }) => {
    const raw = state.raw?.[slot];
    return reply(raw ? previewOf([raw].flat()[0], previewSide) : null);
  },

  /// Samples the chart in `slot` ('chart', or 'chart2', 'chart3', …: an extra chart image). A chart
  /// cut by the frame is sampled where it is inside (SampleOptions.partial): the patches whose
  /// sample area leaves the image are named in `missing`; CORNERS_OUTSIDE when every one does. lightTrap: the four corners of an in-scene light trap (Abed 2013 App. C
  /// step 1) whose mean after the dark frame is subtracted as flare before sampling, or null. A
  /// trap the engine refuses (outside the image, saturated, ...) is not used: the chart is
  /// sampled without it and the reply carries lightTrapError {code, message} for the trap's input.
  sample: (T, { slot = 'chart', layout, corners, sampleOptions = {}, lightTrap = null }, { state }) => {
    const chart = isChart(slot) ? state.raw?.[slot] : null;
    if (!chart) throw coded(`no ${slot === 'chart' ? 'RAW image' : 'extra chart image'} decoded yet (${slot})`, 'NO_IMAGE');
    let trap = null, trapError = null;
    if (lightTrap) {
      try { trap = chart.setLightTrap(lightTrap, sampleOptions); } catch (e) { chart.clearLightTrap(); trapError = { code: e.code, message: e.message }; }
    } else chart.clearLightTrap();
    const s = T.sampleChart(chart, layout, corners, { ...sampleOptions, partial: true });
    s.lightTrap = trap;
    s.lightTrapError = trapError;
    return reply(s);
  },
  /// The patch grid of a layout placed by four corners (for drawing; the engine's homography).
  grid: (T, { layout, corners }) => reply({ layout: T.chartLayout(layout), homography: T.homographyUnitSquare(corners) }),

  /// The SHA-256 of a file's bytes (a recipe's images[k].sha256).
  digest: (T, { bytes }) => ({ result: T.sha256(new Uint8Array(bytes)) }),

  forget: (T, { slot }, { state }) => {
    freeRaw(state.raw?.[slot]);
    delete state.raw?.[slot];
    return { result: calibrateQuietly(state, targetOf(slot) ?? 'chart') };
  },
};

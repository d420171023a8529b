// Worker handlers of step 5: a profile applied to a decoded RAW (the XYZ image stays here,
// state.xyz) rendered for display, and the values of one pixel; the scene RAW's own dark frames,
// flat field and light trap (Abed 2013 App. C step 8), set on it as step 2 sets the chart's.
import { reply, coded } from '../lib/reply.js';
import { renderXYZ, encodingTable, ySample } from './render.js';

export const handlers = {
  /// Applies a profile to a decoded RAW, keeps the XYZ image here and returns display renders.
  applyRender: (T, { profile, slot = 'chart', white, lut, maxSide }, { state, progress }) => {
    const raw = state.raw?.[slot];
    if (!raw) throw coded('no RAW image decoded for this step yet', 'NO_IMAGE');
    progress(NaN, 'applying the profile');
    const t0 = performance.now();
    const img = T.applyProfile(profile, raw);
    const tApply = performance.now() - t0;
    progress(0.7, 'rendering');
    state.xyz = { ...img, white };
    // The Y map's top: the 99th percentile of Y (the engine's quantile, of a subsample).
    const p99 = T.quantile(ySample(img.pixels), 0.99);
    const yMax = p99 > 0 ? p99 : 1;
    const r = renderXYZ(img.pixels, img.width, img.height,
      { matrix: T.displayMatrix(white), enc: encodingTable(T, white), lut: new Uint8Array(lut), maxSide, yMax });
    return reply({ ...r, fullWidth: img.width, fullHeight: img.height, msApply: tApply, msRender: performance.now() - t0 - tApply });
  },

  /// X, Y, Z, x, y and L*a*b* of one pixel of the last applied image.
  pixel: (T, { x, y }, { state }) => {
    const img = state.xyz;
    if (!img) throw coded('no applied image', 'NO_IMAGE');
    const i = Math.floor(y) * img.width + Math.floor(x);
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return { result: null };
    const XYZ = [img.pixels[3 * i], img.pixels[3 * i + 1], img.pixels[3 * i + 2]];
    const s = XYZ[0] + XYZ[1] + XYZ[2];
    return { result: { XYZ, xy: s > 0 ? [XYZ[0] / s, XYZ[1] / s] : [NaN, NaN], Lab: Array.from(T.XYZToLab(XYZ, img.white)) } };
  },

  /// Calibrates the scene RAW with its own frames: `darks` (RAW bytes, averaged), `flat` (RAW
  /// bytes; `flatMode` 'pixel' or 'radial'), `lightTrap` (8 numbers: its corners, whose mean is the
  /// flare subtracted). Replaces what was set before; nothing given: none. Returns what was set.
  sceneFrames: (T, { darks = [], flat = null, flatMode = 'pixel', lightTrap = null }, { state }) => {
    const raw = state.raw?.scene;
    if (!raw) throw coded('no scene RAW decoded yet', 'NO_IMAGE');
    raw.clearDark(); raw.clearFlat(); raw.clearLightTrap();
    const decoded = [];
    try {
      for (const b of darks) decoded.push(T.decodeRaw(new Uint8Array(b)));
      const flatRaw = flat ? T.decodeRaw(new Uint8Array(flat)) : null;
      if (flatRaw) decoded.push(flatRaw);
      const out = { dark: null, flat: null, lightTrap: null };
      if (darks.length) out.dark = raw.setDark(decoded.slice(0, darks.length));
      if (flatRaw) out.flat = raw.setFlat(flatRaw, flatMode);
      if (lightTrap) out.lightTrap = raw.setLightTrap(lightTrap);
      return reply({ dark: out.dark && { frames: out.dark.frames }, flat: !!out.flat, lightTrap: out.lightTrap && { mean: Array.from(out.lightTrap.mean), n: out.lightTrap.n } });
    } catch (e) {
      raw.clearDark(); raw.clearFlat(); raw.clearLightTrap();
      throw e;
    } finally {
      for (const d of decoded) d.delete();
    }
  },
};

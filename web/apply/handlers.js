// Worker handlers of step 5: a profile applied to a decoded RAW (the XYZ image stays here,
// state.xyz) rendered for display, and the values of one pixel.
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

};

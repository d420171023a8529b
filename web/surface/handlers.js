// Worker handlers of the surface step (Abed, Berns & Masaoka 2013): a correction applied to a
// built-in chart's reflectances, Phase I fits of every correction onto a second measurement of
// the chart, and the simulated Table IV.
import { reply, coded } from '../lib/reply.js';

export const handlers = {
  /// The chart's reflectances as measured and as corrected, and the CIEDE2000 between the two
  /// references (Lab under the illuminant and observer of step 1).
  surfacePreview: (T, { chart, choice, illuminant, observer }) => {
    const measured = T.chartReflectances(chart);
    const corrected = T.correctSurface(choice, measured);
    const reference = { chart, illuminant, observer };
    const before = T.recipeReference({ reference });
    const after = T.recipeReference({ reference, surface: choice });
    return reply({ text: T.surfaceChoiceText(typeof choice === 'string' ? T.parseChoice(choice) : choice),
      ids: before.ids, measured, corrected, XYZ_before: before.XYZ, XYZ_after: after.XYZ, sRGB: before.sRGB,
      dE00: T.deltaE('CIE2000', before.Lab, after.Lab) });
  },

  /// Phase I: each start choice fitted from the chart's reflectances onto a second measurement
  /// (a spectral CSV's text), over [range_min, range_max] nm, reported under `illuminant`.
  surfaceCompare: (T, { chart, text, fileName, starts, options, illuminant }, { progress }) => {
    const table = T.parsePatchFile(text, fileName);
    if (!table.has_spectra) throw coded(`${fileName}: no spectral data (a wavelength_nm column and one column per patch)`, 'MISSING_COLUMN');
    const measured = T.chartReflectances(chart);
    const fits = starts.map(({ start, free }, k) => {
      progress(k / starts.length, `fitting ${start.method ?? start}`);
      return T.fitSurface(start, measured, table.spectra, { ...options, free: free ?? 'capture' }, illuminant);   // what `tristim surface fit --json` prints, with the spectra
    });
    const colours = T.referenceChart(chart, illuminant || 'D50', options.observer ?? '1931');   // display colours of the fitted patches
    const at = new Map(colours.ids.map((id, i) => [id, i]));   // both sets' ids are the engine's matching keys
    const sRGB = fits[0].patches.flatMap(({ patch: id }) => { const i = at.get(id); return i === undefined ? [0.5, 0.5, 0.5] : Array.from(colours.sRGB.slice(3 * i, 3 * i + 3)); });
    return reply({ fits, target_ids: table.ids, sRGB: Float64Array.from(sRGB) });
  },

  /// Patch ids as typed ("A01", " b3") -> the engine's matching keys (normalise_patch_id: "A1", "B3").
  patchKeys: (T, { ids }) => ({ result: ids.map((id) => T.normalisePatchId(id)) }),

  /// The simulated Table IV (geometry_table.hpp) for one camera, illuminant and noise σ.
  surfaceTable4: (T, { camera, illuminant, noise }) => reply({ methods: T.surfaceTable4Methods(), cells: T.surfaceTable4(camera, illuminant, noise, 1) }),
};

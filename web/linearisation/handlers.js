// Worker handler of step 2b: one linearisation fitted on the paired chart patches exactly as the
// fit step's recipe will fit it (profile/characterise.cpp builds the same LinearisationData), its
// curves for the plot, the comparison with the grey-based OECF, and the spectral characterisation
// (Shen, Xin, Yang & Lou 2008, eqs 26-28) made with it.
import { reply } from '../lib/reply.js';

const err = (e) => ({ code: e?.code ?? 'INTERNAL', message: String(e?.message ?? e) });

/// Squared Pearson correlation of two equally long arrays (NaN when one is constant).
export function squaredCorrelation(a, b) {
  const n = a.length;
  const ma = a.reduce((s, v) => s + v, 0) / n, mb = b.reduce((s, v) => s + v, 0) / n;
  let sab = 0, saa = 0, sbb = 0;
  for (let i = 0; i < n; i++) { sab += (a[i] - ma) * (b[i] - mb); saa += (a[i] - ma) ** 2; sbb += (b[i] - mb) ** 2; }
  return saa > 0 && sbb > 0 ? (sab * sab) / (saa * sbb) : NaN;
}

/// Column `c` of an N × 3 row-major matrix.
const column = (m, c) => Array.from({ length: m.length / 3 }, (_, i) => m[3 * i + c]);

/// Each channel's curve of `lin` at stored values x·fullScale (x: one channel's abscissae).
function curveAt(T, lin, x, c) {
  const m = new Float64Array(3 * x.length);
  x.forEach((v, i) => { m[3 * i + c] = v * lin.full_scale; });
  return column(T.linearise(lin, m), c);
}

/// The chosen curves against the grey-based OECF, as Shen et al. compare them (Fig 5, Tables I-II):
/// per channel, both sampled at 101 points over the greys' range and scaled to 1 at its top; R² is
/// their squared correlation. Shen2008 does this in the engine (its r_squared and
/// grey_coefficients: the polynomial of the same order K); any other row is compared here, by the
/// same definition, with the engine's grey-polynomial of degree K (3 unless the row has a K). The
/// grey-* rows are the grey-based OECF themselves.
/// `generic`: compare any row here (tests check this path against the engine's Shen2008 R²).
/// The engine's R² per channel (null in its JSON where there is nothing to compare with) as numbers, NaN there.
const r2 = (lin) => lin.r_squared.map((v) => v ?? NaN);

export function compareWithGreys(T, lin, data, { generic = false } = {}) {
  const method = lin.method;
  if (method === 'Shen2008' && !generic) {
    const curves = [0, 1, 2].map((c) => T.sampleCurve(lin, c, 101));
    if (!curves[0].grey_based?.length) return { greys: [], reason: lin.grey_reason, error: null, curves: null };
    return { source: 'engine', greys: lin.greys, reason: lin.grey_reason, r_squared: r2(lin), K: lin.parameters.K,
      curves: curves.map((s) => ({ x: s.x, estimated: s.linear, grey_based: s.grey_based })) };
  }
  if (method.startsWith('grey-') && !generic) return { source: 'self', greys: lin.greys, reason: lin.grey_reason, r_squared: r2(lin), curves: null };
  const K = lin.parameters.K ?? 3;
  const settings = lin.settings.grey !== undefined ? { grey: lin.settings.grey } : {};
  const parameters = { K, ...(lin.parameters.grey_threshold ? { grey_threshold: lin.parameters.grey_threshold } : {}) };
  let g;
  try {
    g = T.fitLinearisation({ method: 'grey-polynomial', parameters, settings }, { ...data, full_scale: lin.full_scale });
  } catch (e) {
    return { greys: [], reason: '', error: err(e), curves: null };
  }
  const r_squared = [], curves = [];
  for (let c = 0; c < 3; c++) {
    const [a, b] = g.domain[c];
    const x = Array.from({ length: 101 }, (_, i) => a + ((b - a) * i) / 100);
    const est = curveAt(T, lin, x, c), grey = curveAt(T, g, x, c);
    r_squared.push(squaredCorrelation(est, grey));
    // The chosen curve over its own range, both scaled to 1 at the top of the greys' range.
    const [a2, b2] = lin.domain[c];
    const x2 = Array.from({ length: 101 }, (_, i) => a2 + ((b2 - a2) * i) / 100);
    curves.push({ x: x2, estimated: curveAt(T, lin, x2, c).map((v) => v / est[100]), x_grey: x, grey_based: grey.map((v) => v / grey[100]) });
  }
  return { source: 'page', greys: g.greys, reason: g.grey_reason, r_squared, K, curves };
}

export const handlers = {
  /// Fits `choice` on the paired patches {ids, rgb (stored values, 3N), xyz (3N), white} with the
  /// chart's reflectances through the surface stage (a built-in chart), at `fullScale` (255, 65535;
  /// 0 for RAW). Returns the fitted Linearisation, its curves, the grey comparison, the linearised
  /// RGB and — with reflectances — the spectral characterisation: per patch estimated reflectance,
  /// spectral RMS (eq 28) and CIEDE2000 under `illuminant`/`observer`, W trained as `spectralChoice`
  /// says (the catalog's `spectral` options; left out: the paper's non-grey patches).
  linearisationFit: (T, { choice, ids, rgb, xyz, white, chart, surface, fullScale, illuminant, observer, spectralChoice }, { progress }) => {
    progress(NaN, `fitting ${choice.method}`);
    const data = { ids, camera_RGB: rgb, reference_XYZ: xyz, white, full_scale: fullScale ?? 0 };
    let measured = null;
    if (chart) {
      measured = T.correctSurface(surface ?? { method: 'none' }, T.chartReflectances(chart));
      data.reflectances = measured;
    }
    const lin = T.fitLinearisation(choice, data);
    const out = { lin, curves: [0, 1, 2].map((c) => T.sampleCurve(lin, c, 101)), linear: T.linearise(lin, rgb), comparison: null, spectral: null };
    try { out.comparison = compareWithGreys(T, lin, data); } catch (e) { out.comparison = { error: err(e), curves: null, greys: [] }; }
    if (measured) {
      progress(NaN, 'spectral characterisation');
      try {
        const model = T.fitSpectral(lin, ids, rgb, measured, spectralChoice ?? { method: '', parameters: {}, settings: {} });
        const est = T.estimateReflectances(model, ids, rgb);
        const ev = T.evaluateSpectral(model, ids, rgb, measured, illuminant ?? 'D65', observer ?? '1931');
        // the measured curves of the fitted patches, in the order of `ids`, on their own grid
        const norm = (id) => String(id).trim().toUpperCase().replace(/^([A-Z]+)0+(\d)/, '$1$2');
        const at = new Map(measured.names.map((n, i) => [norm(n), i]));
        // ev: what `tristim spectral apply --json` prints ({summary, patches: [{patch, spectral_rms, dE00}]})
        out.spectral = { summary: ev.summary, ids: ev.patches.map((p) => p.patch), rms: ev.patches.map((p) => p.spectral_rms), dE00: ev.patches.map((p) => p.dE00),
          training_patches: model.training_patches, training_set: model.training_set, training_ids: model.training_ids,
          greys: model.greys, grey_reason: model.grey_reason, wavelengths: est.wavelengths, estimated: est.values, est_ids: est.names,
          measured: { wavelengths: measured.wavelengths, values: est.names.map((n) => measured.values[at.get(norm(n))] ?? []) } };
      } catch (e) { out.spectral = { error: err(e) }; }
    }
    return reply(out);
  },
};

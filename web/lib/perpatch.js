// Gathers what the plots need for one fitted result, per patch: reference and estimated XYZ and
// Lab, CIEDE2000 with its ΔL/ΔC/ΔH terms, and display colours. XYZ estimates and every ΔE come
// from the engine (fitModel / evaluateProfile), and so do CIELAB coordinates and display sRGB
// (`display`, added by the worker's fit/evaluate handlers from XYZToLab / XYZToDisplaySRGB).
import { cssColours } from '../plots/common.js';

/// A result's patches: {rows, n, white}. result.fit.evaluation is the engine's ModelEvaluation
/// (fitted profiles) or the same shape from evaluateProfile (imported ones); result.fit.display
/// holds the engine's L*a*b* and display sRGB (the worker's fit/evaluate handlers).
export function perPatch(result, reference) {
  const ev = result.fit.evaluation;
  const ids = Array.from(result.ids);
  const n = ids.length;
  const refXYZ = result.xyz, estXYZ = ev.fit.fitted;
  const patches = ev.training.patches;
  const disp = result.fit.display;
  const white = result.white;
  const refIndex = new Map(reference?.ids.map((id, i) => [id, i]) ?? []);
  const refRow = referenceRow(result.recipe, refIndex);
  const refColour = reference ? cssColours(reference.sRGB) : [];
  const estColour = cssColours(disp.estSRGB);
  const ownColour = disp.refSRGB ? cssColours(disp.refSRGB) : [];   // the row's own reference XYZ
  const num = (a, i) => (a && a[i] != null ? a[i] : NaN);
  const rows = ids.map((id, i) => {
    const g = (a, k) => (a ? a[3 * i + k] : NaN);
    const ref = [g(refXYZ, 0), g(refXYZ, 1), g(refXYZ, 2)];
    const est = [g(estXYZ, 0), g(estXYZ, 1), g(estXYZ, 2)];
    // CIELAB against the fit's white, computed by the engine.
    const [L, a, b] = [g(disp.refLab, 0), g(disp.refLab, 1), g(disp.refLab, 2)];
    const [Le, ae, be] = [g(disp.estLab, 0), g(disp.estLab, 1), g(disp.estLab, 2)];
    return {
      id, i,
      X: ref[0], Y: ref[1], Z: ref[2], Xe: est[0], Ye: est[1], Ze: est[2],
      L, a, b, Le, ae, be,
      dE: num(patches.dE00, i), dL: num(patches.dL, i), dC: num(patches.dC, i), dH: num(patches.dH, i),
      fill: refColour[refRow(id)] ?? ownColour[i] ?? '#999', fillEst: estColour[i] ?? '#999',
    };
  });
  for (const r of rows) {
    r.C = Math.hypot(r.a, r.b); r.Ce = Math.hypot(r.ae, r.be);
    const sx = r.X + r.Y + r.Z, se = r.Xe + r.Ye + r.Ze;
    r.x = r.X / sx; r.y = r.Y / sx; r.xe = r.Xe / se; r.ye = r.Ye / se;
  }
  return { rows, n, white };
}

/// The row of `reference` (the first image's) that a training id names. A fit on several chart
/// images (docs/multi-image.md) has ids "k:A1" (or "1+2:A1", one colour shot twice): the k-th
/// image's chart's A1, which is the reference's A1 when that image has the first image's chart
/// (another shot of it); another chart's patches are not in it (undefined: their swatch is drawn
/// from the row's own reference XYZ, the fit's).
function referenceRow(recipe, refIndex) {
  const images = recipe?.images ?? [];
  if (!images.length) return (id) => refIndex.get(id);
  const first = images[0].reference.chart;
  return (id) => {
    const m = /^(\d+)(?:\+\d+)*:(.*)$/.exec(id);
    return m && images[m[1] - 1]?.reference.chart === first ? refIndex.get(m[2]) : undefined;
  };
}

/// Hover text for a patch row.
export function patchTitle(r) {
  const f = (v, d = 2) => (Number.isFinite(v) ? v.toFixed(d) : '–');
  return `${r.id}\nΔE00 ${f(r.dE)} (ΔL ${f(r.dL)}, ΔC ${f(r.dC)}, ΔH ${f(r.dH)})\n`
    + `reference XYZ ${f(r.X)} ${f(r.Y)} ${f(r.Z)}  L*a*b* ${f(r.L, 1)} ${f(r.a, 1)} ${f(r.b, 1)}\n`
    + `estimate  XYZ ${f(r.Xe)} ${f(r.Ye)} ${f(r.Ze)}  L*a*b* ${f(r.Le, 1)} ${f(r.ae, 1)} ${f(r.be, 1)}`;
}

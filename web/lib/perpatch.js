// Gathers what the plots need for one fitted result, per patch: reference and estimated XYZ and
// Lab, CIEDE2000 with its ΔL/ΔC/ΔH terms, and display colours. XYZ estimates and every ΔE come
// from the engine (fitModel / evaluateProfile), and so do CIELAB coordinates and display sRGB
// (`display`, added by the worker's fit/evaluate handlers from XYZToLab / XYZToDisplaySRGB).
import { cssColours } from '../plots/common.js';

/// First defined value among candidate paths ('a.b.c') of obj.
export function pick(obj, ...paths) {
  for (const p of paths) {
    let v = obj;
    for (const k of p.split('.')) { v = v?.[k]; if (v == null) break; }
    if (v != null) return v;
  }
  return undefined;
}

export function perPatch(result, reference) {
  const ev = result.evaluation ?? {};
  const fit = result.fit ?? {};
  const ids = Array.from(result.ids);
  const n = ids.length;
  const refXYZ = result.xyz;
  const estXYZ = pick(ev, 'estimated') ?? pick(fit, 'fitted');
  const patches = pick(ev, 'metrics.patches') ?? pick(fit, 'metrics.training.patches') ?? {};
  const disp = (pick(ev, 'estimated') ? ev.display : fit.display) ?? null;
  const white = disp?.white ?? ev.white ?? result.options?.white ?? reference?.white;
  const refIndex = new Map(reference?.ids.map((id, i) => [id, i]) ?? []);
  const refColour = reference ? cssColours(reference.sRGB) : [];
  const estColour = disp ? cssColours(disp.estSRGB) : [];
  const num = (a, i) => (a && a[i] != null ? a[i] : NaN);
  const rows = ids.map((id, i) => {
    const g = (a, k) => (a ? a[3 * i + k] : NaN);
    const ref = [g(refXYZ, 0), g(refXYZ, 1), g(refXYZ, 2)];
    const est = [g(estXYZ, 0), g(estXYZ, 1), g(estXYZ, 2)];
    // CIELAB against the fit's white, computed by the engine.
    const [L, a, b] = disp ? [g(disp.refLab, 0), g(disp.refLab, 1), g(disp.refLab, 2)] : [NaN, NaN, NaN];
    const [Le, ae, be] = disp ? [g(disp.estLab, 0), g(disp.estLab, 1), g(disp.estLab, 2)] : [NaN, NaN, NaN];
    return {
      id, i,
      X: ref[0], Y: ref[1], Z: ref[2], Xe: est[0], Ye: est[1], Ze: est[2],
      L, a, b, Le, ae, be,
      dE: num(patches.dE00, i), dL: num(patches.dL, i), dC: num(patches.dC, i), dH: num(patches.dH, i),
      fill: refColour[refIndex.get(id)] ?? '#999', fillEst: estColour[i] ?? '#999',
    };
  });
  for (const r of rows) {
    r.C = Math.hypot(r.a, r.b); r.Ce = Math.hypot(r.ae, r.be);
    const sx = r.X + r.Y + r.Z, se = r.Xe + r.Ye + r.Ze;
    r.x = r.X / sx; r.y = r.Y / sx; r.xe = r.Xe / se; r.ye = r.Ye / se;
  }
  return {
    rows, n, white,
    has: { estXYZ: !!estXYZ, Lab: !!disp, dE: !!patches.dE00, parts: !!(patches.dL && patches.dC && patches.dH) },
  };
}

/// Hover text for a patch row.
export function patchTitle(r) {
  const f = (v, d = 2) => (Number.isFinite(v) ? v.toFixed(d) : '–');
  return `${r.id}\nΔE00 ${f(r.dE)} (ΔL ${f(r.dL)}, ΔC ${f(r.dC)}, ΔH ${f(r.dH)})\n`
    + `reference XYZ ${f(r.X)} ${f(r.Y)} ${f(r.Z)}  L*a*b* ${f(r.L, 1)} ${f(r.a, 1)} ${f(r.b, 1)}\n`
    + `estimate  XYZ ${f(r.Xe)} ${f(r.Ye)} ${f(r.Ze)}  L*a*b* ${f(r.Le, 1)} ${f(r.ae, 1)} ${f(r.be, 1)}`;
}

// Gathers what the plots need for one fitted result, per patch: reference and estimated XYZ and
// Lab, CIEDE2000 with its ΔL/ΔC/ΔH terms, and display colours. Everything numeric comes from the
// engine (fitModel / evaluateProfile); only display sRGB is computed here.
import { XYZ_to_display_sRGB } from './display.js';
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
  const src = { ...fit, ...ev };
  const ids = Array.from(pick(src, 'ids') ?? result.ids);
  const n = ids.length;
  const refXYZ = pick(src, 'referenceXYZ', 'reference.XYZ', 'XYZ_reference') ?? result.xyz;
  const estXYZ = pick(src, 'estimatedXYZ', 'estimated.XYZ', 'XYZ_estimated', 'predictedXYZ', 'XYZ');
  const refLab = pick(src, 'referenceLab', 'reference.Lab', 'Lab_reference');
  const estLab = pick(src, 'estimatedLab', 'estimated.Lab', 'Lab_estimated', 'predictedLab');
  const dE = pick(src, 'dE2000', 'perPatch.dE2000', 'CIE2000', 'deltaE2000', 'dE00');
  const dL = pick(src, 'dL', 'dE2000_dL', 'perPatch.dL');
  const dC = pick(src, 'dC', 'dE2000_dC', 'perPatch.dC');
  const dH = pick(src, 'dH', 'dE2000_dH', 'perPatch.dH');
  const white = reference?.white ?? [96.42, 100, 82.49];
  const refIndex = new Map(reference?.ids.map((id, i) => [id, i]) ?? []);
  const refColour = reference ? cssColours(reference.sRGB) : [];
  const estColour = estXYZ ? cssColours(XYZ_to_display_sRGB(estXYZ, white)) : [];
  const rows = ids.map((id, i) => {
    const g = (a, k) => (a ? a[3 * i + k] : NaN);
    return {
      id, i,
      X: g(refXYZ, 0), Y: g(refXYZ, 1), Z: g(refXYZ, 2),
      Xe: g(estXYZ, 0), Ye: g(estXYZ, 1), Ze: g(estXYZ, 2),
      L: g(refLab, 0), a: g(refLab, 1), b: g(refLab, 2),
      Le: g(estLab, 0), ae: g(estLab, 1), be: g(estLab, 2),
      dE: dE?.[i] ?? NaN, dL: dL?.[i] ?? NaN, dC: dC?.[i] ?? NaN, dH: dH?.[i] ?? NaN,
      fill: refColour[refIndex.get(id)] ?? '#999', fillEst: estColour[i] ?? '#999',
    };
  });
  for (const r of rows) {
    r.C = Math.hypot(r.a, r.b); r.Ce = Math.hypot(r.ae, r.be);
    const sx = r.X + r.Y + r.Z, se = r.Xe + r.Ye + r.Ze;
    r.x = r.X / sx; r.y = r.Y / sx; r.xe = r.Xe / se; r.ye = r.Ye / se;
  }
  return {
    rows, n,
    has: { estXYZ: !!estXYZ, Lab: !!(refLab && estLab), dE: !!dE, parts: !!(dL && dC && dH) },
  };
}

/// Hover text for a patch row.
export function patchTitle(r) {
  const f = (v, d = 2) => (Number.isFinite(v) ? v.toFixed(d) : '–');
  return `${r.id}\nΔE00 ${f(r.dE)} (ΔL ${f(r.dL)}, ΔC ${f(r.dC)}, ΔH ${f(r.dH)})\n`
    + `reference XYZ ${f(r.X)} ${f(r.Y)} ${f(r.Z)}  L*a*b* ${f(r.L, 1)} ${f(r.a, 1)} ${f(r.b, 1)}\n`
    + `estimate  XYZ ${f(r.Xe)} ${f(r.Ye)} ${f(r.Ze)}  L*a*b* ${f(r.Le, 1)} ${f(r.ae, 1)} ${f(r.be, 1)}`;
}

// Copies what the engine returns into plain JS objects that own their memory (typed arrays are
// sliced out of the wasm heap, TOOLCHAIN gotcha 6) so they can be transferred to the page.
export function plain(v) {
  if (ArrayBuffer.isView(v)) return v.slice();
  if (Array.isArray(v)) return v.map(plain);
  if (v && typeof v === 'object') {
    if (typeof v.delete === 'function' && typeof v.constructor === 'function' && v.$$) return v; // embind object
    const out = {};
    for (const k of Object.keys(v)) out[k] = plain(v[k]);
    return out;
  }
  return v;
}

const f64 = (a) => (a == null ? a : a instanceof Float64Array ? a : Float64Array.from(a));

/// referenceChart / parseReferenceFile -> {ids, XYZ, Lab, sRGB, white, ...}
export function referenceOut(r) {
  const o = plain(r);
  return { ...o, ids: Array.from(o.ids), XYZ: f64(o.XYZ), Lab: f64(o.Lab), sRGB: f64(o.sRGB), white: Array.from(o.white ?? []) };
}

/// sampleChart -> {ids, RGB, std, n, saturatedFraction, flags, ...}
export function sampleOut(s) {
  const o = plain(s);
  const ids = Array.from(o.ids);
  return { ...o, ids, RGB: f64(o.RGB), std: f64(o.std), flagNames: flagNames(o.flags, ids.length) };
}

/// Per-patch flags as lists of words, whatever the engine's encoding (strings, lists, or bits).
export const FLAG_BITS = ['saturated', 'too dark', 'non-uniform'];
export function flagNames(flags, n) {
  const out = [];
  for (let i = 0; i < n; i++) {
    const f = flags?.[i];
    if (f == null || f === '' || f === 0) out.push([]);
    else if (Array.isArray(f)) out.push(f.map(String));
    else if (typeof f === 'number') out.push(FLAG_BITS.filter((_, b) => f & (1 << b)));
    else out.push(String(f).split(/[|,;\s]+/).filter(Boolean));
  }
  return out;
}

/// fitModel -> {profile (JSON string), ...metrics}
export function fitOut(f) {
  const o = plain(f);
  if (typeof o.profile !== 'string') o.profile = JSON.stringify(o.profile);
  return o;
}

export const evaluationOut = plain;


// Worker-side helpers shared by the features' handlers.

/// Buffers of every typed array found in a (nested) plain object.
function buffers(obj, out = []) {
  if (ArrayBuffer.isView(obj)) out.push(obj.buffer);
  else if (obj && typeof obj === 'object') for (const v of Object.values(obj)) buffers(v, out);
  return [...new Set(out)];
}
/// A handler's reply: the result, with every typed array's buffer transferred to the page (the
/// engine's results own their arrays; nothing points into the wasm heap).
export const reply = (result) => ({ result, transfer: buffers(result) });

/// A coded error for a request the worker cannot answer yet.
export const coded = (message, code) => Object.assign(new Error(message), { code });

/// L*a*b* of reference and estimate and display sRGB of both, from the engine (CIE 15 Lab;
/// Bradford to D65 + sRGB for display), for the Lab planes and swatches of the results.
export function displayOf(T, refXYZ, estXYZ, white) {
  return { white: Array.from(white), refLab: T.XYZToLab(refXYZ, white), estLab: T.XYZToLab(estXYZ, white), estSRGB: T.XYZToDisplaySRGB(estXYZ, white),
    refSRGB: T.XYZToDisplaySRGB(refXYZ, white) };
}

// Pairs sampled camera RGB with reference XYZ by patch id (the ids are shared by layouts and
// reference data), leaving out patches whose flags `exclude(flags)` rejects (default: saturated).
export function pairData(sample, reference, { exclude = (f) => f.includes('saturated') } = {}) {
  const refIndex = new Map(reference.ids.map((id, i) => [id, i]));
  const ids = [], rgb = [], xyz = [], excluded = [], missing = [];
  sample.ids.forEach((id, i) => {
    const j = refIndex.get(id);
    if (j === undefined) { missing.push(id); return; }
    if (exclude(sample.flags?.[i] ?? [])) { excluded.push({ id, flags: sample.flags[i] }); return; }
    ids.push(id);
    rgb.push(sample.RGB[3 * i], sample.RGB[3 * i + 1], sample.RGB[3 * i + 2]);
    xyz.push(reference.XYZ[3 * j], reference.XYZ[3 * j + 1], reference.XYZ[3 * j + 2]);
  });
  return { ids, rgb: Float64Array.from(rgb), xyz: Float64Array.from(xyz), excluded, missing };
}

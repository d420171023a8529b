// The page's one way to pair sampled camera RGB with reference XYZ: the engine's pairing
// (trainingSet, profile/characterise.hpp), the one the fit, its leave-one-out and
// `tristim fit --recipe` train on. In the sample's order; by normalised patch id; leaving out the
// ids of the recipe's `sampling.exclude` and the patches with a flag `sampling.exclude_flags` lists
// (or, with `sampling.exclude_flagged`, any flag).

/// The ids of `sample`'s patches whose flags `rule(flags)` leaves out.
export const excludedBy = (sample, rule) => sample.ids.filter((id, i) => rule(sample.flags?.[i] ?? []));

/// The sample flags the fit step leaves out (its recipes' sampling.exclude_flags), in the engine's
/// table's order (`rows`: catalog.sampleFlags): the fit step's choice; for a session saved before
/// the choice was a list, its two toggles (excludeAllFlagged: every flag; excludeSaturated off:
/// none); otherwise the table's defaults (the rows with default 1).
export function excludeFlags(fitChoice, rows) {
  const names = rows.map((f) => f.name);
  if (Array.isArray(fitChoice?.excludeFlags)) return names.filter((n) => fitChoice.excludeFlags.includes(n));
  if (fitChoice?.excludeAllFlagged) return names;
  if (fitChoice?.excludeSaturated === false) return [];
  return rows.filter((f) => f.default_number === 1).map((f) => f.name);
}

/// Pairs a ChartSample (`patches`, `missing`) with a ReferenceChart through the engine's worker.
/// Resolves to {ids, labels, rgb, xyz, excluded} (`excluded`: the engine's "A3 (saturated)" lines);
/// rejects with its coded error: PATCH_MISMATCH (a sampled patch not in the reference),
/// TOO_FEW_PATCHES (every patch left out).
export async function pairData(engine, sample, reference, sampling = {}) {
  const { layout, homography, patches, missing = [] } = sample;
  const { source, settings, data_digest, ...ref } = reference;   // the engine's ReferenceChart
  const t = await engine.call('pairSample', { sampling, sample: { layout, homography, patches, missing }, reference: ref });
  return { ids: t.ids, labels: t.labels, rgb: t.camera_RGB, xyz: t.reference_XYZ, excluded: t.excluded };
}

/// The fit step's held-out set {name, ids, rgb, xyz, withoutRGB} from a patch file `{name, text}`:
/// a file with its own X, Y, Z columns as it is; one with R, G, B only paired with `reference`
/// (step 1) as a chart sample is (pairData, the engine's pair_by_id). Either way in the file's
/// order, as `tristim evaluate --rgb` and `tristim compare --test-rgb/--test-xyz` pair it.
/// `withoutRGB`: the reference's patches the file lacks (as the reference spells them), which
/// `tristim evaluate` names on stderr too. Rejects with a coded error: MISSING_COLUMN (no R, G, B),
/// NO_REFERENCE, or the engine's PATCH_MISMATCH naming the file.
export async function heldOutSet(engine, file, reference) {
  const p = await engine.call('parsePatchFile', { text: file.text, fileName: file.name });
  if (!p.has_RGB) throw Object.assign(new Error(`${file.name} has no R, G, B columns`), { code: 'MISSING_COLUMN' });
  let ids = p.ids, rgb = p.RGB, xyz = p.XYZ, withoutRGB = [];
  if (!p.has_XYZ) {
    if (!reference) throw Object.assign(new Error('no reference to pair the held-out patches with (step 1)'), { code: 'NO_REFERENCE' });
    const patches = ids.map((id, i) => ({ id, mean: [rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]] }));
    ({ ids, rgb, xyz } = await pairData(engine, { patches }, reference).catch((e) => { throw Object.assign(new Error(`${file.name}: ${e.message}`), { code: e.code }); }));
    const held = new Set(ids);
    withoutRGB = reference.ids.map((id, i) => (held.has(id) ? null : reference.labels?.[i] ?? id)).filter((id) => id != null);
  }
  return { name: file.name, ids, rgb: Float64Array.from(rgb), xyz: Float64Array.from(xyz), withoutRGB };
}

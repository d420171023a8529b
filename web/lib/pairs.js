// The page's one way to pair sampled camera RGB with reference XYZ: the engine's pairing
// (trainingSet, profile/characterise.hpp), the one the fit, its leave-one-out and
// `tristim fit --recipe` train on. In the sample's order; by normalised patch id; leaving out the
// ids of the recipe's `sampling.exclude` and, with `sampling.exclude_flagged`, every flagged patch.

/// The ids of `sample`'s patches whose flags `rule(flags)` leaves out (the recipe's
/// sampling.exclude list the page writes for its "leave out saturated" toggle).
export const excludedBy = (sample, rule) => sample.ids.filter((id, i) => rule(sample.flags?.[i] ?? []));

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

// Worker handler of step 3: one fit of a recipe (the engine's Recipe) on the chart sample paired
// with the reference, with its display colours and its errors on a held-out set; and the bootstrap
// of a fitted result in steps (the engine's BootstrapRun, kept here between the page's calls so a
// cancel message is taken between two chunks).
import { reply, displayOf, coded } from '../lib/reply.js';

/// The union of the training sets of a recipe's images (`charts`: their samples and references);
/// the Share step's link of such a fit is made on it too (web/share/handlers.js).
export function unionOf(T, recipe, charts) {
  if (charts?.length !== recipe.images.length) throw coded(`the recipe lists ${recipe.images.length} images but ${charts?.length ?? 0} samples were given`, 'INVALID_ARGUMENT');
  return T.trainingUnion(recipe, recipe.images.map((entry, k) => {
    const own = T.imageRecipe(recipe, entry);
    return { name: entry.name, training: T.trainingSet(own, charts[k].sample, own.reference.chart === 'file' ? charts[k].reference : T.recipeReference(own)) };
  }));
}

export const handlers = {
  /// A measured patch file (CSV/CGATS with R,G,B and maybe X,Y,Z) for a held-out test set.
  parsePatchFile: (T, { text, fileName }) => reply(T.parsePatchFile(text, fileName)),

  /// A chart sample paired with a reference as the fit pairs it (the engine's trainingSet, with
  /// the recipe's `sampling` exclusion rules): web/lib/pairs.js is the page's caller.
  pairSample: (T, { sampling, sample, reference }) => reply(T.trainingSet({ sampling }, sample, reference)),

  /// Fits a recipe on the chart sample paired with the reference (and evaluates the profile on
  /// the held-out set {name, ids, rgb, xyz} when there is one).
  /// `worker_ms`: how long the row ran here (the page's log; timed on the page, a row that waited
  /// in the worker's queue, or whose reply waited for the page's busy thread, read 1 ms or 2×).
  /// With `recipe.images` (several chart images, issue 48): `charts` [{sample, reference}] one per
  /// entry, in order; each sample is paired with its entry's reference (a built-in chart's through
  /// the engine, a file's as given), and the fit trains on the union — `tristim fit --recipe` with
  /// one --raw per image; `out.charts` holds each chart's figures.
  fit: (T, { recipe, sample, reference, heldOut, charts }, { progress }) => {
    const t0 = performance.now();
    progress(NaN, `fitting ${recipe.characterisation.model}`);
    if (heldOut) recipe.evaluation.held_out_digest = T.trainingDigest(heldOut.ids, heldOut.rgb, heldOut.xyz);
    // A built-in chart with a surface correction: the reference is the recipe's (the chart's
    // spectra through the surface stage), so the profile is trained on what the recipe records.
    const corrected = recipe.reference.chart !== 'file' && (recipe.surface?.method ?? 'none') !== 'none';
    const out = recipe.images?.length ? T.fitTraining(recipe, unionOf(T, recipe, charts))
      : T.fitSample(recipe, sample, corrected ? T.recipeReference(recipe) : reference);
    out.display = displayOf(T, out.reference_XYZ, out.evaluation.fit.fitted, out.recipe.characterisation.lab_white);
    out.objective_label = T.objectiveChoiceLabel(recipe.characterisation.objective);   // the loss and optimiser it ran
    if (heldOut) out.held_out = { ...T.evaluateProfile(out.profile, heldOut.rgb, heldOut.xyz, heldOut.ids).metrics, set: heldOut.name };
    out.worker_ms = performance.now() - t0;
    return reply(out);
  },

  /// Starts the bootstrap of a fitted result (the engine's bootstrapRecipe: the recipe's fit on its
  /// training set; `settings` a choice of the bootstrapOptions table; `pixels` {std, n} of the
  /// sampled patches, or null: patches only); a run in progress is dropped.
  bootstrapStart: (T, { recipe, ids, rgb, xyz, loo, settings, pixels }, { state }) => {
    state.bootstrap?.delete();
    state.bootstrap = null;
    state.bootstrap = T.bootstrapRecipe(recipe, ids, rgb, xyz, loo, settings, pixels ?? null);
    return { result: { done: 0, total: state.bootstrap.total() } };
  },
  /// Runs the next `count` resamples of the current run.
  bootstrapStep: (T, { count }, { state }) => {
    const run = state.bootstrap;
    if (!run) throw coded('no bootstrap is running (it was cancelled or never started)', 'INVALID_ARGUMENT');
    run.step(count);
    return { result: { done: run.done(), total: run.total() } };
  },
  /// The run's intervals and covariances, and `profile` (JSON text) with them added; ends the run.
  bootstrapResult: (T, { profile }, { state }) => {
    const run = state.bootstrap;
    if (!run) throw coded('no bootstrap is running (it was cancelled or never started)', 'INVALID_ARGUMENT');
    try {
      return reply({ bootstrap: run.result(), profile: profile ? run.profileWith(profile) : null });
    } finally {
      run.delete();
      state.bootstrap = null;
    }
  },
  /// Drops the current run (the page's Cancel).
  bootstrapCancel: (T, _msg, { state }) => {
    state.bootstrap?.delete();
    state.bootstrap = null;
    return { result: { cancelled: true } };
  },

  /// `tristim compare`'s two checks of a fitted result (the engine's recipeStoppingCheck and
  /// recipeRidgeRow): does its leave-one-out mean move when the optimiser stops 100× later, and
  /// its model by ridge least squares with λ chosen by leave-one-out.
  looStability: (T, { recipe, ids, rgb, xyz, loo_mean, condition_number }) =>
    reply(T.recipeStoppingCheck(recipe, ids, rgb, xyz, loo_mean, condition_number)),
  ridgeRow: (T, { recipe, ids, rgb, xyz }) => reply(T.recipeRidgeRow(recipe, ids, rgb, xyz)),
};

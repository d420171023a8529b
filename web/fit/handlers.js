// Worker handler of step 3: one fit of a recipe (the engine's Recipe) on the chart sample paired
// with the reference, with its display colours and its errors on a held-out set.
import { reply, displayOf } from '../lib/reply.js';

export const handlers = {
  /// A measured patch file (CSV/CGATS with R,G,B and maybe X,Y,Z) for a held-out test set.
  parsePatchFile: (T, { text, fileName }) => reply(T.parsePatchFile(text, fileName)),

  /// Fits a recipe on the chart sample paired with the reference (and evaluates the profile on
  /// the held-out set {name, ids, rgb, xyz} when there is one).
  /// `worker_ms`: how long the row ran here (the page's log; timed on the page, a row that waited
  /// in the worker's queue, or whose reply waited for the page's busy thread, read 1 ms or 2×).
  fit: (T, { recipe, sample, reference, heldOut }, { progress }) => {
    const t0 = performance.now();
    progress(NaN, `fitting ${recipe.characterisation.model}`);
    if (heldOut) recipe.evaluation.held_out_digest = T.trainingDigest(heldOut.ids, heldOut.rgb, heldOut.xyz);
    // A built-in chart with a surface correction: the reference is the recipe's (the chart's
    // spectra through the surface stage), so the profile is trained on what the recipe records.
    const corrected = recipe.reference.chart !== 'file' && (recipe.surface?.method ?? 'none') !== 'none';
    const out = T.fitSample(recipe, sample, corrected ? T.recipeReference(recipe) : reference);
    out.display = displayOf(T, out.reference_XYZ, out.evaluation.fit.fitted, out.recipe.characterisation.lab_white);
    out.objective_label = T.objectiveChoiceLabel(recipe.characterisation.objective);   // the loss and optimiser it ran
    if (heldOut) out.held_out = { ...T.evaluateProfile(out.profile, heldOut.rgb, heldOut.xyz, heldOut.ids).metrics, set: heldOut.name };
    out.worker_ms = performance.now() - t0;
    return reply(out);
  },
};

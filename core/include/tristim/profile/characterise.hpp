// From a recipe and its inputs to a profile: the one data path the CLI and the page share.
//
//   chart sample (or patch tables) ─┐
//   reference (built-in chart → surface stage → illuminant/observer, or a file) ─┴→ training set
//   → linearisation stage → model + objective → training / leave-one-out metrics → profile
//
// The profile embeds the (completed) recipe, so `tristim fit --recipe` on the same inputs
// reproduces it.
#pragma once
#include <string>
#include <vector>

#include "tristim/chart/layout.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/profile/recipe.hpp"

namespace tristim {

/// The reference of a recipe whose reference.chart is built in: the chart's reflectances through
/// the surface stage (surface/surface.hpp), integrated under reference.illuminant and
/// reference.observer. Error(InvalidArgument) when reference.chart is "file" (read the file and
/// use reference_from_table instead).
ReferenceChart recipe_reference(const Recipe& recipe);

/// Patches that go into the fit, paired by id.
struct TrainingSet {
  std::vector<std::string> ids;       ///< the patches' keys (normalise_patch_id): what pairs and digests use
  std::vector<std::string> labels;    ///< the same patches as the user's data spell them (a reference or
                                      ///< patch file's "A01", "Q001"): what per-patch outputs write
  PatchMatrix camera_RGB;     ///< as sampled (before the linearisation stage), N × 3
  PatchMatrix reference_XYZ;  ///< N × 3, Y = 100 for the perfect diffuser
  std::vector<std::string> excluded;  ///< ids left out, with the reason: "A3 (nonuniform)"
};

/// Pairs a chart sample with a reference by patch id, leaving out the recipe's sampling.exclude
/// ids and, with sampling.exclude_flagged, every flagged patch. Error(PatchMismatch) when a
/// sampled patch is not in the reference; Error(TooFewPatches) when nothing is left. Labels: the
/// reference's (a user file's own spelling; the layout's ids for a built-in chart).
TrainingSet training_set(const Recipe& recipe, const ChartSample& sample, const ReferenceChart& reference);
/// The same from paired tables (rows already matched by id). `ids` as the user's file spells them
/// (or already normalised): they are the labels, their normalised forms the keys.
TrainingSet training_set(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                         const PatchMatrix& reference_XYZ);

struct Characterisation {
  Recipe recipe;                 ///< completed
  Linearisation linearisation;   ///< the fitted linearisation stage (identity for RAW)
  PatchMatrix linear_RGB;        ///< the training camera RGB after linearisation
  PatchMatrix reference_XYZ;     ///< the training reference XYZ as fitted (after a joint surface fit)
  ModelEvaluation evaluation;    ///< fit, training and leave-one-out metrics
  int white_index = -1;          ///< row of the preserved white patch, or -1
  /// The surface correction the training reference went through: the recipe's, or, when its
  /// `fit` option is "joint", the Phase II result (fit "fixed", so it reproduces that reference).
  MethodChoice surface{"none", {}, {}};
  std::string surface_status;    ///< Phase II only: "ok", "at_bound", "iteration_limit" (+ message)
  Profile profile;               ///< embeds the recipe
};

/// Runs the linearisation, characterisation and evaluation stages of `recipe` on `training`.
/// A surface stage with fit "joint" (Phase II, surface/joint.hpp) is fitted here, on the linear
/// RGB, jointly with a 3×3 anchored to the white patch (characterisation.white_patch, required:
/// it stands in for the paper's PTFE, its reflectance taken as flat at its measured Y/Y_white);
/// the training reference XYZ are then those of the fitted correction. Needs a built-in chart.
Characterisation characterise(const Recipe& recipe, const TrainingSet& training);

}  // namespace tristim

// Declarations: the Recipe (every stage of a characterisation as a value) and the one data path
// from a recipe and its inputs to a profile (profile/characterise.hpp). A Recipe crosses as the
// object its JSON is (its field lists, tristim/profile/recipe.hpp; members left out keep their
// defaults), or as its JSON text.
// Several chart images (issue 48, docs/multi-image.md), as `tristim fit --recipe` with an `images`
// list: trainingSet(imageRecipe(recipe, recipe.images[k]), sample_k, reference_k) per chart, then
// fitTraining(recipe, trainingUnion(recipe, [{name, training}, …])) — its `charts` the per-chart figures,
// each the object `tristim fit` writes in the profile's "charts" ({chart, patches, training, loo,
// held_out, held_out_error}; ChartFigures' field list, characterise.hpp).
#include "tristim/profile/characterise.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

namespace {

/// What a fit hands back to the page: the completed recipe, the training set as fitted (after
/// the linearisation stage), the evaluation and the profile JSON (which embeds the recipe).
/// `labels`: the training patches as the user's reference file spells them (the per-patch CSV's ids).
struct FitOutcome {
  Recipe recipe;
  std::vector<std::string> ids, labels, excluded;
  PatchMatrix linear_RGB, reference_XYZ;
  ModelEvaluation evaluation;
  std::string profile;
  MethodChoice surface;          // the correction the reference went through (Phase II: the fitted one)
  std::string surface_status;
  std::vector<ChartFigures> charts;  // several charts: each one's figures, the objects of the profile's "charts" (its field list)
};
FitOutcome outcome(const Recipe& recipe, const TrainingSet& training) {
  const Characterisation c = characterise(recipe, training);
  return {c.recipe, training.ids, training.labels, training.excluded, c.linear_RGB, c.reference_XYZ, c.evaluation, profile_to_json(c.profile),
          c.surface, c.surface_status, chart_figures(c, training)};
}
/// fitSample(recipe, sample, reference): a chart sample paired with a reference by patch id.
FitOutcome fit_sample(const Recipe& recipe, const ChartSample& sample, const ReferenceChart& reference) {
  return outcome(recipe, training_set(recipe, sample, reference));
}
/// fitTables(recipe, ids, rgb, xyz): patch tables already paired row by row.
FitOutcome fit_tables(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& rgb, const PatchMatrix& xyz) {
  return outcome(recipe, training_set(recipe, ids, rgb, xyz));
}

TrainingSet sample_training_set(const Recipe& recipe, const ChartSample& sample, const ReferenceChart& reference) {
  return training_set(recipe, sample, reference);
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_recipe) {
  { using S = TrainingSet; value_object<S>("TrainingSet") FIELD(ids) FIELD(labels) FIELD(camera_RGB) FIELD(reference_XYZ)
      FIELD(excluded) FIELD(chart_names) FIELD(chart_rows); }
  { using S = ChartPart; value_object<S>("ChartPart") FIELD(name) FIELD(training); }
  { using S = FitOutcome; value_object<S>("FitOutcome") FIELD(recipe) FIELD(ids) FIELD(labels) FIELD(excluded) FIELD(linear_RGB)
      FIELD(reference_XYZ) FIELD(evaluation) FIELD(profile) FIELD(surface) FIELD(surface_status) FIELD(charts); }

  def<&fit_sample>("fitSample");
  def<&fit_tables>("fitTables");
  def<&outcome>("fitTraining");
  def<&sample_training_set>("trainingSet");
  def<&image_recipe>("imageRecipe");
  def<&training_union>("trainingUnion");
  def<&recipe_reference>("recipeReference");
  def<&complete_recipe>("completeRecipe");
  def<&recipe_to_json>("recipeToJson");
  def<static_cast<Recipe (*)(const std::string&)>(&recipe_from_json)>("recipeFromJson");
  def<&bytes_digest>("bytesDigest");
}

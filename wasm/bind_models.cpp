// Declarations: characterisation fits and their evaluation, the model × objective comparison,
// profiles (a Profile argument may be given as the profile JSON text) and their exports.
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/export.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using emscripten::value_object;
using wasm::Conv;
using wasm::def;

namespace {

/// Leave-one-out metrics cross as null when there are none.
val loo_of(const ModelEvaluation& e) { return e.has_loo ? Conv<Metrics>::to(e.loo) : val::null(); }

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_models) {
  using wasm::set_field;
  { using S = PatternSearchOptions; value_object<S>("PatternSearchOptions") FIELD(initial_step) FIELD(expansion)
      FIELD(contraction) FIELD(step_threshold) FIELD(max_iterations); }
  { using S = DeltaE2000Options; value_object<S>("DeltaE2000Options") FIELD(algorithm) FIELD(xtol_rel) FIELD(ftol_rel)
      FIELD(max_evaluations) FIELD(rms) FIELD(initial_step); }
  { using S = FitOptions; value_object<S>("FitOptions") FIELD(objective) FIELD(white) FIELD(weights) FIELD(preserve_white)
      FIELD(white_RGB) FIELD(white_XYZ) FIELD(psm) FIELD(de2000) FIELD(warn_condition) FIELD(max_condition); }
  { using S = Model; value_object<S>("Model") FIELD(id) FIELD(coefficients); }
  { using S = FitResult; value_object<S>("FitResult") FIELD(model) FIELD(objective) FIELD(status) FIELD(message)
      FIELD(iterations) FIELD(evaluations) FIELD(condition_number) FIELD(objective_value) FIELD(start_objective_value)
      FIELD(white_preserved) FIELD(fitted) FIELD(residuals) FIELD(mu); }
  { using S = Summary; value_object<S>("Summary") FIELD(min) FIELD(median) FIELD(mean) FIELD(p95) FIELD(max) FIELD(rms) FIELD(std); }
  { using S = PatchErrors; value_object<S>("PatchErrors") FIELD(dE76) FIELD(dE94) FIELD(dE00) FIELD(dL) FIELD(dC) FIELD(dH)
      FIELD(dE_xyz) FIELD(rel_Y); }
  { using S = Metrics; value_object<S>("Metrics") FIELD(patches) FIELD(dE76) FIELD(dE94) FIELD(dE00) FIELD(dE_xyz)
      FIELD(abs_rel_Y) FIELD(NRMSE); }
  { using S = ModelEvaluation; value_object<S>("ModelEvaluation") FIELD(fit) FIELD(fit_seconds) FIELD(fit_cpu_seconds)
      FIELD(training) FIELD(has_loo) .field("loo", &loo_of, &set_field<&S::loo>) FIELD(loo_XYZ); }
  { using S = CompareRow; value_object<S>("CompareRow") FIELD(model_id) FIELD(objective) FIELD(n_terms) FIELD(ok)
      FIELD(error_code) FIELD(message) FIELD(status) FIELD(condition_number) FIELD(seconds) FIELD(cpu_seconds)
      FIELD(train_dE00) FIELD(loo_dE00) FIELD(train_dE_xyz) FIELD(loo_dE_xyz) FIELD(has_loo); }
  { using S = StoppingCheck; value_object<S>("StoppingCheck") FIELD(checked) FIELD(flagged) FIELD(loo_mean)
      FIELD(perturbed_loo_mean); }
  { using S = RidgeRow; value_object<S>("RidgeRow") FIELD(row) FIELD(lambda); }
  { using S = Profile; value_object<S>("Profile") FIELD(version) FIELD(tristim_version) FIELD(model) FIELD(objective)
      FIELD(white) FIELD(illuminant) FIELD(observer) FIELD(white_preserved) FIELD(white_patch) FIELD(white_RGB)
      FIELD(white_XYZ) FIELD(training_patches) FIELD(training_digest) FIELD(rgb_max) FIELD(status) FIELD(message)
      FIELD(condition_number) FIELD(iterations) FIELD(objective_value) FIELD(has_recipe) FIELD(recipe)
      FIELD(has_linearisation) FIELD(linearisation); }
  { using S = IccOptions; value_object<S>("IccOptions") FIELD(rgb_scale) FIELD(grid_points) FIELD(shaper_gamma)
      FIELD(description) FIELD(version); }

  def<&evaluate_model>("evaluateModel");
  def<&compare_models>("compareModels");
  def<&recipe_stopping_check>("recipeStoppingCheck");
  def<&recipe_ridge_row>("recipeRidgeRow");
  def<&profile_from_json>("profileFromJson");
  def<static_cast<PatchMatrix (*)(const Model&, const PatchMatrix&)>(&predict)>("predict");
  def<&evaluate>("evaluate");
  def<&quantile>("quantile");
  def<&training_digest>("trainingDigest");
  def<&profile_predict>("profilePredict");
  def<&export_icc>("exportIcc");
  def<&export_cube>("exportCube");
  def<&patch_csv>("patchCsv");
}

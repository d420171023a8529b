// Declarations: characterisation fits and their evaluation, the model × objective comparison (its
// rows, ridge rows and stopping checks cross by their field lists: what tristim compare --json
// prints), profiles (a Profile crosses as its document, or its JSON text: wasm/types.hpp) and their
// exports.
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/export.hpp"
#include "declare.hpp"
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
  STRUCT(PatternSearchOptions, initial_step, expansion, contraction, step_threshold, max_iterations);
  STRUCT(DeltaE2000Options, algorithm, xtol_rel, ftol_rel, max_evaluations, rms, initial_step);
  STRUCT(FitOptions, objective, white, weights, preserve_white, white_RGB, white_XYZ, psm, de2000, warn_condition,
           max_condition);
  STRUCT(Model, id, coefficients);
  STRUCT(FitResult, model, objective, status, message, iterations, evaluations, condition_number, objective_value,
           start_objective_value, white_preserved, fitted, residuals, mu);
  { using S = ModelEvaluation; value_object<S>("ModelEvaluation") FIELD(fit) FIELD(fit_seconds) FIELD(fit_cpu_seconds)
      FIELD(training) FIELD(has_loo) .field("loo", &loo_of, &set_field<&S::loo>) FIELD(loo_XYZ); }
  STRUCT(IccOptions, rgb_scale, grid_points, shaper_gamma, description, version);

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

// Evaluation of characterisation models: per-patch colour differences, summaries, training
// vs leave-one-out error, train-on-one-chart / test-on-another, and a model × objective table.
//
// All errors compare an estimate with a reference in the same XYZ units; CIELAB differences
// use a stated white in those units.
#pragma once
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/io/fields.hpp"

namespace tristim {

struct Recipe;

/// min, median, mean, 95th percentile (linear interpolation between order statistics, as
/// numpy's default), max, RMS (sqrt of mean square) and population standard deviation.
struct Summary {
  double min = 0, median = 0, mean = 0, p95 = 0, max = 0, rms = 0, std = 0;
};
Summary summarize(const std::vector<double>& values);
/// The q-quantile (0 <= q <= 1) of the finite values, by Summary's rule (linear interpolation
/// between order statistics): the one percentile of the engine, which the page's colour-map
/// ranges use too. NaN when no value is finite; Error(InvalidArgument) for q outside [0, 1].
double quantile(std::vector<double> values, double q);

/// Per-patch errors of an estimate against a reference (vectors of N).
struct PatchErrors {
  std::vector<double> dE76, dE94, dE00;  ///< CIE 1976, CIE 1994 (graphic arts), CIEDE2000
  std::vector<double> dL, dC, dH;        ///< CIEDE2000 weighted components (estimate − reference)
  std::vector<double> dE_xyz;            ///< Euclidean XYZ distance, data units
  std::vector<double> rel_Y;             ///< (Y_est − Y_ref) / Y_ref (NaN where Y_ref = 0)
};

struct Metrics {
  PatchErrors patches;
  Summary dE76, dE94, dE00, dE_xyz;
  Summary abs_rel_Y;  ///< summary of |rel_Y| over patches with Y_ref > 0
  /// NRMSE per X, Y, Z. Guarnera 2018 (Tables 4-5) reports it without a formula; we use
  /// NRMSE_c = sqrt(mean_i (c_est,i − c_ref,i)²) / (max_i c_ref,i − min_i c_ref,i),
  /// the RMS error normalised by the range of the reference channel.
  Vec3 NRMSE = Vec3::Zero();
};

/// Errors of estimated_XYZ against reference_XYZ (N × 3 each), CIELAB relative to `white`.
Metrics evaluate(const PatchMatrix& estimated_XYZ, const PatchMatrix& reference_XYZ,
                 const Vec3& white = whites::D50());

/// Leave-one-out predictions: row i is predicted by the model fitted (same id and options)
/// to every patch except i. With white preservation, the fold that holds out the white patch
/// (`white_patch_index`, −1 for none) is fitted without the constraint, so no patch is ever
/// predicted by a fit that saw it. Error(TooFewPatches) if N − 1 patches cannot fit the model.
/// Least squares: the closed form (leave_one_out_least_squares, no refits). Iterative objectives
/// refit every fold from that fold's own least-squares start: a start from the full fit (which saw
/// the held-out patch) leaks it into flat or under-determined folds (tried: Finlayson2015-4 psm
/// on the Passport gave a leave-one-out mean ΔE00 of 0.09 instead of 39.8), so none is used.
PatchMatrix leave_one_out(const std::string& model_id, const PatchMatrix& camera_RGB,
                          const PatchMatrix& reference_XYZ, const FitOptions& options = {},
                          int white_patch_index = -1);

/// Whether a leave-one-out figure depends on where the optimiser stops (issue 47: Finlayson2015-3
/// de2000 on the Passport gave 5.56 / 5.66 / 6.79 across three stopping points). The leave-one-out
/// mean CIEDE2000 is computed again with every stopping tolerance 100× tighter (de2000 xtol_rel and
/// ftol_rel, psm step_threshold); `flagged` when it moves by more than 0.05 or 2 % of `loo_mean`.
/// Only iterative objectives whose training fit's condition number exceeds `min_condition` are
/// checked (least squares has one answer; a well-conditioned loss has a sharp minimum).
struct StoppingCheck {
  bool checked = false;
  bool flagged = false;
  double loo_mean = 0;            ///< as given
  double perturbed_loo_mean = 0;  ///< with the tighter tolerances
};
StoppingCheck leave_one_out_stopping_check(const std::string& model_id, const PatchMatrix& camera_RGB,
                                           const PatchMatrix& reference_XYZ, const FitOptions& options,
                                           int white_patch_index, double loo_mean, double condition_number,
                                           double min_condition = 1e4);

/// A fit with its training and leave-one-out metrics.
struct ModelEvaluation {
  FitResult fit;
  double fit_seconds = 0;      ///< wall time of the training fit alone
  double fit_cpu_seconds = 0;  ///< process CPU time of the training fit (robust on a busy machine)
  Metrics training;
  bool has_loo = false;  ///< false when N − 1 patches are too few for the model
  Metrics loo;
  PatchMatrix loo_XYZ;
};
ModelEvaluation evaluate_model(const std::string& model_id, const PatchMatrix& camera_RGB,
                               const PatchMatrix& reference_XYZ, const FitOptions& options = {},
                               int white_patch_index = -1, bool with_loo = true);

/// One row of the compare table.
struct CompareRow {
  std::string model_id;
  Objective objective = Objective::LeastSquares;
  int n_terms = 0;
  bool ok = false;          ///< false: the fit was refused (see error_code, message)
  std::string error_code;   ///< e.g. "TOO_FEW_PATCHES" when !ok
  std::string message;      ///< the error, or the fit's warning
  FitStatus status = FitStatus::Ok;
  double condition_number = 0;
  double seconds = 0;       ///< wall time of the training fit (without leave-one-out)
  double cpu_seconds = 0;   ///< process CPU time of the same
  Summary train_dE00, loo_dE00, train_dE_xyz, loo_dE_xyz;
  bool has_loo = false;
};

/// Every (non-duplicate) model × objective on the same data, sorted by held-out (LOO) mean
/// CIEDE2000, then training mean; refused fits last. `model_ids` empty: every model of the
/// table that is not a duplicate; `objectives` empty: ls, psm, de2000.
std::vector<CompareRow> compare_models(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                                       const FitOptions& options = {},
                                       std::vector<std::string> model_ids = {},
                                       std::vector<Objective> objectives = {}, int white_patch_index = -1);

/// A model fitted by ridge least squares (characterisation/ridge.hpp, λ by leave-one-out) as a row
/// of the comparison: training and leave-one-out metrics against options.white; `lambda` the
/// chosen λ (relative to σ_max²). A refused fit is a row with ok = false, its code and message.
struct RidgeRow {
  CompareRow row;
  double lambda = 0;
};
RidgeRow ridge_row(const std::string& model_id, const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                   const FitOptions& options = {});

/// The two checks `tristim compare` makes, for one fit made from `recipe` (recipe_fit_options: its
/// objective, lab white, white patch) on its training set (`ids`, camera RGB after linearisation,
/// reference XYZ), as the page asks them of a result: whether its leave-one-out mean `loo_mean`
/// depends on where the optimiser stops (leave_one_out_stopping_check), and its model fitted by
/// ridge least squares (ridge_row; without the recipe's white constraint, which ridge lacks).
StoppingCheck recipe_stopping_check(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                                    const PatchMatrix& reference_XYZ, double loo_mean, double condition_number);
RidgeRow recipe_ridge_row(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                          const PatchMatrix& reference_XYZ);

/// Natively, compare_models spreads its rows over at most this many threads (0, the default: one
/// per hardware thread, at most 16). The wasm build always runs the rows in order on one thread
/// (the page spreads them over workers instead). Process-wide; Error(InvalidArgument) if n < 0.
void set_compare_threads(int n);
int compare_threads();

/// A named training set (for the transfer table).
struct NamedPatches {
  std::string name;
  PatchMatrix camera_RGB, reference_XYZ;
};

/// Abed 2013 Table IV layout: for each training set (rows) and model × objective (columns),
/// the mean and max ΔE_xyz and CIEDE2000 on one fixed test set.
struct TransferCell {
  std::string training_set, model_id;
  Objective objective = Objective::LeastSquares;
  bool ok = false;
  std::string error_code, message;
  Summary dE_xyz, dE00;
};
std::vector<TransferCell> transfer_table(const std::vector<NamedPatches>& training,
                                         const PatchMatrix& test_RGB, const PatchMatrix& test_XYZ,
                                         const std::vector<std::string>& model_ids,
                                         const std::vector<Objective>& objectives,
                                         const FitOptions& options = {});

}  // namespace tristim

// Field lists (io/fields.hpp), defined in evaluation.cpp: a Summary and the per-patch errors are
// the objects their JSON is (a figure that is not a number, null); Metrics' list is its summaries
// (the form profiles and reports store), its per-patch errors are written beside their ids
// (metrics_json with per_patch) and cross to JS as `patches` (wasm/types.hpp).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(Summary);
TRISTIM_FIELDS_DECLARE(PatchErrors);
TRISTIM_FIELDS_DECLARE(Metrics);
// The compare table (what `tristim compare --json` prints, the names and order of its rows): a
// CompareRow's model id is "model", its objective its id, its status "error" when the fit was
// refused (read back as the default status), leave-one-out summaries only when it has them. A
// RidgeRow is its row's members, then "ridge": true and "lambda". A StoppingCheck's list is all its
// members (the CLI prints two of them). A TransferCell's list leaves out `message`.
TRISTIM_FIELDS_DECLARE(CompareRow);
TRISTIM_FIELDS_DECLARE(StoppingCheck);
TRISTIM_FIELDS_DECLARE(RidgeRow);
TRISTIM_FIELDS_DECLARE(TransferCell);
}  // namespace tristim::fields

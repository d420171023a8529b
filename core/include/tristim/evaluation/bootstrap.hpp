// Bootstrap confidence intervals for a fitted characterisation (issue 47): how sure a profile's
// figures are. Each resample draws N patches with replacement (Efron's pairs bootstrap, over the
// patches) and, where per-patch pixel statistics exist (sample's R_std,G_std,B_std,n), replaces
// each drawn patch's mean camera RGB by the mean of a resample of its pixels — drawn from that
// mean's sampling distribution, normal with σ = std/√n (the pixels themselves are not kept; for
// the hundreds of pixels a patch has this is the resampled mean's distribution to within the
// normal approximation). The model is refitted (same id, objective and options) and:
//   - each coefficient's percentile interval at `level` (and the 3P × 3P covariance of the
//     coefficients, row-major order M(0,0), M(0,1), …, M(2,P−1)), both widened about the full fit
//     by √(N/(N − q)) (q free coefficients per channel), the HC1 small-sample correction;
//   - the training mean CIEDE2000 of each refit on its own resampled patches;
//   - the leave-one-out mean CIEDE2000 over the resampled patches, from the per-patch
//     leave-one-out errors of the full fit (the patch-sampling uncertainty of the held-out mean);
//   - per patch, the covariance of the predicted XYZ, chromaticity xy and CIELAB a*b* over the
//     refits, widened by the same f² (Cov(ŷ) = J Cov(β) Jᵀ with the widened Cov(β)): the ellipses
//     of the page's xy and a*b* plots, x'Σ⁻¹x = k² with k² = ν((1 − level)^(−2/ν) − 1), ν = N − q
//     (Hotelling's F(2, ν) quantile, Σ being estimated from N patches; → −2 ln(1 − level), the
//     two-dimensional normal's, for many patches).
// A run can be stepped in chunks (BootstrapRun: the page's worker takes a cancel between chunks);
// the result depends only on the seed, never on the chunking.
// Random numbers: splitmix64 with the seed, uniform indices by multiply-shift and normal
// deviates by Marsaglia's polar method with detmath's log, so a seed gives the same intervals
// natively and in wasm.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tristim/characterisation/fit.hpp"
#include "tristim/io/json.hpp"
#include "tristim/methods.hpp"

namespace tristim {

struct Recipe;

/// A confidence interval: [lo, hi] at `level` (percentile bootstrap).
struct Interval {
  double level = 0.95;
  double lo = 0, hi = 0;
};

struct BootstrapOptions {
  int resamples = 1000;   ///< 1 … 100000
  uint64_t seed = 1;
  double level = 0.95;    ///< in (0, 1)
  /// Per-patch pixel statistics (both empty, or N × 3 and N): the standard deviation of each
  /// patch's pixels per channel and the number of pixels averaged. Empty: patches only.
  PatchMatrix pixel_std;
  std::vector<double> pixel_count;
  /// The full fit's per-patch leave-one-out CIEDE2000 (N values; empty: no leave-one-out interval).
  std::vector<double> loo_dE00;
  /// Called after resample `done` of `total` (every ~2 %); returning false stops the bootstrap,
  /// whose result then covers the resamples done so far and says `cancelled`.
  std::function<bool(int done, int total)> progress;
};

struct BootstrapResult {
  int resamples = 0;        ///< refits that succeeded (the intervals' sample)
  int failed = 0;           ///< resamples whose refit was refused (e.g. a constant channel)
  bool cancelled = false;
  bool pixels = false;      ///< pixel statistics were resampled too
  double level = 0.95;
  uint64_t seed = 1;
  double inflation = 1;     ///< √(N/(N − q)) applied to the coefficients' intervals and covariance, squared to the predictions' (bootstrap.cpp)
  Interval train_dE00_mean;
  bool has_loo = false;
  Interval loo_dE00_mean;
  Eigen::MatrixXd coefficients_lo, coefficients_hi;  ///< 3 × P
  Eigen::MatrixXd covariance;                        ///< 3P × 3P, row-major order of the coefficients
  std::vector<Mat3> predicted_XYZ_covariance;        ///< per patch (the original patches' RGB), widened as `covariance`
  std::vector<Eigen::Matrix2d> predicted_xy_covariance;  ///< per patch, chromaticity x, y (CIE 15 eq 7.3)
  std::vector<Eigen::Matrix2d> predicted_ab_covariance;  ///< per patch, CIELAB a*, b* (FitOptions::white)
  double ellipse_scale = 0;  ///< k = √(ν((1 − level)^(−2/ν) − 1)), ν = N − q: the ellipse x'Σ⁻¹x = k² (F(2, ν) at `level`)
};

/// The bootstrap's settings as the page's form shows them and `--bootstrap`, `--seed`, `--level`
/// take them: "resamples" (integer 1 … 100000, default 1000), "seed" (integer ≥ 0, default 1),
/// "level" (strictly between 0 and 1, default 0.95).
MethodInfo bootstrap_option_table();

/// A bootstrap in steps: the same resamples, in the same order, as bootstrap_fit (which is one run
/// stepped to the end), so a seed gives the same result however the run is chunked.
class BootstrapRun {
 public:
  /// Checks the options and fits the data as given (errors as bootstrap_fit's); runs nothing yet.
  BootstrapRun(const std::string& model_id, const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
               const FitOptions& options, const BootstrapOptions& bootstrap);
  /// Runs up to `count` more resamples (never past the total); returns how many are done.
  int step(int count);
  int done() const { return done_; }
  int total() const { return bootstrap_.resamples; }
  /// The full fit's model (the centre of the coefficients' intervals).
  const Model& model() const { return full_.model; }
  /// The intervals from the resamples done so far; `cancelled` when fewer than total().
  /// Error(NoUsableData) when fewer than two refits succeeded.
  BootstrapResult result() const;

 private:
  std::string model_id_;
  PatchMatrix rgb_, xyz_;
  FitOptions options_, refit_options_;
  BootstrapOptions bootstrap_;
  FitResult full_;
  std::vector<Eigen::Vector2d> full_xy_, full_ab_;
  uint64_t random_state_ = 0;
  int done_ = 0, resamples_ = 0, failed_ = 0;
  Eigen::MatrixXd coefficients_;
  std::vector<double> train_, loo_;
  std::vector<Eigen::Vector3d> sum_x_;
  std::vector<Mat3> sum_xx_;
  std::vector<Eigen::Vector4d> sum_xy_ab_;  ///< per patch: Σ of (x, y, a*, b*) deviations
  std::vector<Eigen::Matrix4d> sum_xy_ab2_;
};

/// The bootstrap of a recipe's fit as characterise() made it (recipe_fit_options: objective, lab
/// white, preserved white patch) on its training set (`ids`, camera RGB after linearisation,
/// reference XYZ), with the fit's per-patch leave-one-out CIEDE2000 (empty: none) and `settings`
/// a choice of bootstrap_option_table() (missing options take its defaults). `pixel_std` (N × 3)
/// and `pixel_count` (N), in the order of `ids`: the sampled pixels' statistics (BootstrapOptions),
/// resampled too when given and the recipe's linearisation is "identity" (the statistics are of
/// raw DN, which only the identity leaves as they are), as `tristim fit --recipe r.json --rgb
/// p.csv --xyz … --bootstrap N --seed S --level L` does when p.csv is `tristim sample`'s (its
/// R_std, G_std, B_std, n); otherwise patches only, the same resamples as that line without them.
BootstrapRun bootstrap_recipe(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                              const PatchMatrix& reference_XYZ, const std::vector<double>& loo_dE00,
                              const MethodChoice& settings, const PatchMatrix& pixel_std = PatchMatrix(),
                              const std::vector<double>& pixel_count = {});

/// `profile` (a profile JSON object, as profile_to_json writes it) with the bootstrap added: "ci"
/// next to "mean" of metrics.training.dE00 and metrics.loo.dE00, and "bootstrap": bootstrap_json.
void add_bootstrap_to_profile(json::Value& profile, const BootstrapResult& result, const Model& fitted);
/// The profile JSON text `profile_json` with `run`'s bootstrap added (add_bootstrap_to_profile),
/// written as `tristim fit --bootstrap` writes its profile.
std::string profile_with_bootstrap(const std::string& profile_json, const BootstrapRun& run);

/// `summary` (a summary_json object) with "ci" set next to its "mean".
json::Value summary_with_ci(const json::Value& summary, const Interval& ci);

/// The bootstrap of `fit(model_id, camera_RGB, reference_XYZ, options)` described above.
/// Errors: InvalidArgument (resamples, level, pixel statistics of the wrong size or negative),
/// the fit's own errors for the data as given; NoUsableData when fewer than two refits succeed.
BootstrapResult bootstrap_fit(const std::string& model_id, const PatchMatrix& camera_RGB,
                              const PatchMatrix& reference_XYZ, const FitOptions& options,
                              const BootstrapOptions& bootstrap);

/// Percentile interval of `values` (finite ones) at `level`: the (1 − level)/2 and (1 + level)/2
/// quantiles by the engine's quantile rule.
Interval percentile_interval(const std::vector<double>& values, double level);

/// {"level", "lo", "hi"}: the "ci" object of the CLI's and the page's JSON.
json::Value interval_json(const Interval& interval);
/// The bootstrap as JSON: {"resamples", "failed", "cancelled", "seed", "level", "resampling"
/// ("patches" | "patches+pixels"), "inflation", "coefficients": 3 rows of P {"value", "ci"} (value:
/// `fitted`'s coefficient), "covariance": 3P rows of 3P numbers (row-major coefficient order),
/// "predicted_XYZ_covariance": per patch a 3 × 3 array, "predicted_xy_covariance" and
/// "predicted_ab_covariance": per patch a 2 × 2 array, "ellipse_scale"}.
json::Value bootstrap_json(const BootstrapResult& result, const Model& fitted);

}  // namespace tristim

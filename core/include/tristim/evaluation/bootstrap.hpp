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
//   - per patch, the covariance of the predicted XYZ over the refits (ellipses on the xy / a*b*
//     plots).
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

namespace tristim {

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
  double inflation = 1;     ///< √(N/(N − q)) applied to the coefficients' intervals and covariance (bootstrap.cpp)
  Interval train_dE00_mean;
  bool has_loo = false;
  Interval loo_dE00_mean;
  Eigen::MatrixXd coefficients_lo, coefficients_hi;  ///< 3 × P
  Eigen::MatrixXd covariance;                        ///< 3P × 3P, row-major order of the coefficients
  std::vector<Mat3> predicted_XYZ_covariance;        ///< per patch (the original patches' RGB)
};

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
/// "predicted_XYZ_covariance": per patch a 3 × 3 array}.
json::Value bootstrap_json(const BootstrapResult& result, const Model& fitted);

}  // namespace tristim

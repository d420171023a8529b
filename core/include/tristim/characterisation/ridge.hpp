// Ridge (Tikhonov) least squares for the many-term models, the penalty chosen by leave-one-out
// (issue 47): min Σ‖XYZ − M·φ(RGB)‖² + λ‖M_s‖², M_s the coefficients in the equilibrated
// coordinates of fit.hpp (each design column scaled to unit norm), so λ does not depend on the
// units of RGB or XYZ. For a fixed λ the fit is a linear smoother, ŷ = H·y with
// H = A(AᵀA + λI)⁻¹Aᵀ, so its leave-one-out predictions are closed form, y_k − e_k/(1 − h_kk)
// (Allen's PRESS identity, as for least squares, leave_one_out_least_squares). λ is the value of
// the grid {0} ∪ {10^(−10 + i/4) · σ_max², i = 0…44} (σ_max the design's largest singular value)
// whose leave-one-out mean CIEDE2000 is smallest (ties: the smaller λ), the figure `compare`
// sorts by. λ = 0 is plain least squares, so the chosen fit is never worse held-out.
#pragma once
#include <string>
#include <vector>

#include "tristim/characterisation/fit.hpp"

namespace tristim {

struct RidgeResult {
  FitResult fit;                       ///< at the chosen λ (objective ls; message names λ)
  double lambda = 0;                   ///< chosen λ, relative to σ_max²
  std::vector<double> lambdas;         ///< the grid (relative), ascending, 0 first
  std::vector<double> loo_dE00_mean;   ///< leave-one-out mean CIEDE2000 per grid value (NaN: a fold undetermined)
  PatchMatrix loo_XYZ;                 ///< leave-one-out predictions at the chosen λ
};

/// Ridge fit of `model_id` (any model of the table but corrected-3x3) as described above, CIELAB
/// relative to options.white. Errors: as fit()'s least squares; InvalidArgument with white
/// preservation or another objective; TooFewPatches below 3 patches.
RidgeResult fit_ridge(const std::string& model_id, const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                      const FitOptions& options = {});

}  // namespace tristim

// Leave-one-out predictions of the least-squares fit in closed form (PRESS residuals).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "fit_problem.hpp"
#include "tristim/error.hpp"

namespace tristim {

PatchMatrix leave_one_out_least_squares(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                                        const FitOptions& options, int white_patch_index) {
  const ModelInfo& info = model_info(model_id);
  if (info.id == kCorrected3x3)
    throw Error(ErrorCode::InvalidArgument, "leave-one-out: '" + info.id + "' has no closed form (refit each fold: leave_one_out)");
  FitOptions o = options;
  o.objective = Objective::LeastSquares;
  const fit_detail::Problem pr = fit_detail::make_problem(info, rgb, xyz, o);
  if (pr.n - 1 < std::max(pr.q, 1))
    throw Error(ErrorCode::TooFewPatches, "leave-one-out: " + std::to_string(pr.n - 1) + " patches cannot fit '" +
                                              info.id + "' (" + std::to_string(pr.q) + " free coefficients)");
  double cond = 0;
  const Eigen::MatrixXd z = fit_detail::solve_ls(pr, o, cond);
  const Eigen::MatrixXd E = pr.Y - pr.predictions(z);  // N × 3 training residuals
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(pr.B);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(pr.n, pr.q);  // thin Q: H = Q·Qᵀ
  PatchMatrix out(pr.n, 3);
  for (Eigen::Index k = 0; k < pr.n; ++k) {
    // A fold must refuse what a refit would refuse: a channel constant over the remaining patches.
    const int constant = fit_detail::constant_channel(rgb, k);
    if (constant >= 0)
      throw Error(ErrorCode::IllConditioned, "leaving out patch " + std::to_string(k + 1) +
                                                 " makes camera channel " + "RGB"[constant] + " constant");
    if (k == white_patch_index && o.preserve_white) {
      // The white patch's own fold is fitted without the constraint (it may not see its patch).
      FitOptions u = o;
      u.preserve_white = false;
      u.warn_condition = INFINITY;
      PatchMatrix r(pr.n - 1, 3), x(pr.n - 1, 3);
      for (Eigen::Index i = 0, j = 0; i < pr.n; ++i)
        if (i != k) r.row(j) = rgb.row(i), x.row(j++) = xyz.row(i);
      out.row(k) = predict(fit_detail::fit_info(info, r, x, u).model, Vec3(rgb.row(k).transpose())).transpose();
      continue;
    }
    // PRESS residual (Allen 1974): the fold without patch k predicts y_k − e_k / (1 − h_kk). With the
    // white constraint the fit is unconstrained least squares in the null-space coordinates (B, z),
    // so the same identity holds there.
    const double leverage = Q.row(k).squaredNorm();
    if (!(1 - leverage > 1e-10))
      throw Error(ErrorCode::IllConditioned, "leaving out patch " + std::to_string(k + 1) +
                                                 " leaves model '" + info.id + "' undetermined (leverage 1)");
    out.row(k) = pr.Y.row(k) - E.row(k) / (1 - leverage);
  }
  return out;
}

}  // namespace tristim

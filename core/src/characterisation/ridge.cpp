// Ridge least squares with λ by closed-form leave-one-out (characterisation/ridge.hpp).
#include "tristim/characterisation/ridge.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "fit_problem.hpp"
#include "tristim/error.hpp"

namespace tristim {

RidgeResult fit_ridge(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                      const FitOptions& options) {
  const ModelInfo& info = model_info(model_id);
  if (info.id == kCorrected3x3) throw Error(ErrorCode::InvalidArgument, "ridge: '" + info.id + "' is not a least-squares model");
  if (options.objective != Objective::LeastSquares)
    throw Error(ErrorCode::InvalidArgument, "ridge: the penalty is on the least-squares objective (ls)");
  if (options.preserve_white)
    throw Error(ErrorCode::InvalidArgument, "ridge: white-point preservation is not supported (the white's fold)");
  if (rgb.rows() < 3) throw Error(ErrorCode::TooFewPatches, "ridge: needs at least 3 patches");
  const fit_detail::Problem pr = fit_detail::make_problem(info, rgb, xyz, options);
  double cond = 0;
  fit_detail::solve_ls(pr, options, cond);  // the same refusals as least squares (a singular design)
  // B = U·S·Vᵀ; z(λ) = V·diag(s/(s² + λ))·Uᵀ·Y; h_kk(λ) = Σ_j U_kj² s_j²/(s_j² + λ).
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(pr.B, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const Eigen::MatrixXd& U = svd.matrixU();
  const Eigen::MatrixXd UtY = U.transpose() * pr.Y;
  const double smax2 = s(0) * s(0);
  RidgeResult out;
  out.lambdas.push_back(0);
  for (int i = 0; i <= 44; ++i) out.lambdas.push_back(std::pow(10.0, -10 + i / 4.0));
  const auto solve = [&](double lambda, PatchMatrix& loo) {
    const Eigen::VectorXd f = s.array() / (s.array().square() + lambda * smax2);
    const Eigen::MatrixXd z = svd.matrixV() * f.asDiagonal() * UtY;
    const Eigen::MatrixXd fitted = pr.predictions(z);
    const Eigen::VectorXd shrink = s.array().square() * f.array() / s.array();  // s²/(s² + λ)
    loo.resize(pr.n, 3);
    for (Eigen::Index k = 0; k < pr.n; ++k) {
      const double h = (U.row(k).array().square() * shrink.transpose().array()).sum();
      if (!(1 - h > 1e-10)) return Eigen::MatrixXd();
      loo.row(k) = pr.Y.row(k) - (pr.Y.row(k) - fitted.row(k)) / (1 - h);
    }
    return z;
  };
  double best = INFINITY;
  for (double lambda : out.lambdas) {
    PatchMatrix loo;
    const Eigen::MatrixXd z = solve(lambda, loo);
    double mean = std::nan("");
    if (z.size() > 0) {
      mean = 0;
      for (Eigen::Index k = 0; k < pr.n; ++k)
        mean += delta_E_CIE2000(XYZ_to_Lab(xyz.row(k).transpose(), options.white), XYZ_to_Lab(loo.row(k).transpose(), options.white));
      mean /= static_cast<double>(pr.n);
    }
    out.loo_dE00_mean.push_back(mean);
    if (mean < best) {
      best = mean;
      out.lambda = lambda;
    }
  }
  if (!std::isfinite(best))
    throw Error(ErrorCode::IllConditioned, "ridge: every leave-one-out fold of '" + info.id + "' is undetermined");
  const Eigen::MatrixXd z = solve(out.lambda, out.loo_XYZ);
  FitResult& r = out.fit;
  r.model.id = info.id;
  r.model.coefficients = pr.coefficients(z);
  r.objective = Objective::LeastSquares;
  r.condition_number = cond;
  r.fitted = predict(r.model, rgb);
  r.residuals = r.fitted - xyz;
  r.objective_value = std::sqrt(r.residuals.squaredNorm() / (3.0 * static_cast<double>(pr.n)));
  r.start_objective_value = r.objective_value;
  std::ostringstream m;
  m << "ridge: lambda = " << out.lambda << " x sigma_max^2, chosen by leave-one-out mean dE00";
  r.message = m.str();
  return out;
}

}  // namespace tristim

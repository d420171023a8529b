// Ridge least squares with λ by closed-form leave-one-out (characterisation/ridge.hpp): λ = 0 is
// least squares, the closed form against brute-force refits with the same penalty (an independent
// normal-equations solve), a many-term model on noisy patches, refusals.
#include <Eigen/Dense>
#include <cmath>

#include "../evaluation/bootstrap_sim.hpp"
#include "test_support.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/ridge.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {
double mean_dE00(const PatchMatrix& est, const PatchMatrix& ref) { return evaluate(est, ref).dE00.mean; }
}  // namespace

TEST_CASE("ridge: lambda = 0 is least squares, and the chosen lambda is never worse held-out", "[characterisation][ridge]") {
  test::Simulation sim{11};
  PatchMatrix rgb, xyz;
  test::simulate_chart(sim, rgb, xyz, 1.0);
  const RidgeResult r = fit_ridge("Cheung2004-10", rgb, xyz);
  REQUIRE(r.lambdas.front() == 0);
  const PatchMatrix loo_ls = leave_one_out_least_squares("Cheung2004-10", rgb, xyz);
  CHECK(r.loo_dE00_mean.front() == Approx(mean_dE00(loo_ls, xyz)).epsilon(1e-9));
  CHECK(mean_dE00(r.loo_XYZ, xyz) <= r.loo_dE00_mean.front() + 1e-12);
  CHECK(r.fit.model.id == "Cheung2004-10");
  CHECK(r.fit.message.find("ridge") != std::string::npos);
}

TEST_CASE("ridge: a 10-term polynomial on 24 noisy patches of a linear camera is shrunk", "[characterisation][ridge]") {
  // The truth is a 3×3 (test::planted_matrix): the extra terms only fit noise, which ridge damps.
  test::Simulation sim{5};
  PatchMatrix rgb, xyz;
  test::simulate_chart(sim, rgb, xyz, 2.0);
  const RidgeResult r = fit_ridge("Cheung2004-10", rgb, xyz);
  INFO("lambda " << r.lambda << ", loo " << mean_dE00(r.loo_XYZ, xyz) << " vs ls " << r.loo_dE00_mean.front());
  CHECK(r.lambda > 0);
  CHECK(mean_dE00(r.loo_XYZ, xyz) < r.loo_dE00_mean.front());
  // Noiseless linear data and a 3×3: nothing to damp, λ = 0 recovers the planted matrix.
  test::simulate_chart(sim, rgb, xyz, 0.0);
  const RidgeResult exact = fit_ridge("matrix-3x3", rgb, xyz);
  CHECK(exact.lambda == 0);
  CHECK((exact.fit.model.coefficients - test::planted_matrix()).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("ridge: the closed-form leave-one-out equals refits with the same penalty", "[characterisation][ridge]") {
  test::Simulation sim{9};
  PatchMatrix rgb, xyz;
  test::simulate_chart(sim, rgb, xyz, 1.5, 20);
  const RidgeResult r = fit_ridge("Finlayson2015-2", rgb, xyz);
  // Independent: the design and its column scales from the full data, each fold solved by the
  // normal equations (AᵀA + λσ²I) z = AᵀY.
  const ModelInfo& info = model_info("Finlayson2015-2");
  const Eigen::Index n = rgb.rows(), p = info.n_terms;
  Eigen::MatrixXd A(n, p);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::vector<double> phi = expansion("Finlayson2015-2", Vec3(rgb.row(i).transpose()));
    for (Eigen::Index j = 0; j < p; ++j) A(i, j) = phi[static_cast<size_t>(j)];
  }
  for (Eigen::Index j = 0; j < p; ++j) A.col(j) /= A.col(j).norm();
  const double smax = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues()(0);
  double worst = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::MatrixXd Af(n - 1, p), Yf(n - 1, 3);
    for (Eigen::Index i = 0, j = 0; i < n; ++i)
      if (i != k) Af.row(j) = A.row(i), Yf.row(j++) = xyz.row(i);
    const Eigen::MatrixXd M = Af.transpose() * Af + r.lambda * smax * smax * Eigen::MatrixXd::Identity(p, p);
    const Eigen::MatrixXd z = M.ldlt().solve(Af.transpose() * Yf);
    worst = std::max(worst, (A.row(k) * z - r.loo_XYZ.row(k)).cwiseAbs().maxCoeff());
  }
  INFO("lambda " << r.lambda << ", worst difference " << worst);
  CHECK(worst < 1e-8);
}

TEST_CASE("ridge: refusals", "[characterisation][ridge]") {
  test::Simulation sim{2};
  PatchMatrix rgb, xyz;
  test::simulate_chart(sim, rgb, xyz, 1.0);
  FitOptions o;
  o.objective = Objective::PatternSearch;
  require_code([&] { fit_ridge("matrix-3x3", rgb, xyz, o); }, ErrorCode::InvalidArgument);
  o = FitOptions{};
  o.preserve_white = true;
  o.white_RGB = Vec3(50, 50, 50);
  o.white_XYZ = Vec3(50, 50, 50);
  require_code([&] { fit_ridge("matrix-3x3", rgb, xyz, o); }, ErrorCode::InvalidArgument);
  require_code([&] { fit_ridge(kCorrected3x3, rgb, xyz); }, ErrorCode::InvalidArgument);
  require_code([&] { fit_ridge("matrix-3x3", rgb.topRows(2), xyz.topRows(2)); }, ErrorCode::TooFewPatches);
}

// Bootstrap intervals (evaluation/bootstrap.hpp): coverage of a planted truth on simulated charts,
// determinism by seed, pixel statistics, cancellation and refusals.
#include <cmath>
#include <cstdio>

#include <Eigen/LU>

#include "bootstrap_sim.hpp"
#include "test_support.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/bootstrap.hpp"
#include "tristim/evaluation/evaluation.hpp"

using namespace tristim;
using tristim::test::require_code;

using test::resampling;
using test::Simulation;
using test::simulated_chart;

// The full check (1,000 simulated charts × 1,000 resamples) runs in tests/bench/bench_bootstrap.cpp
// and prints its coverage; here a smaller version: 300 charts × 200 resamples, 9 coefficients each (2,700 intervals:
// the binomial standard error is 0.4 %; the full run gives 0.943).
TEST_CASE("bootstrap: 95 % intervals of a 3x3 least-squares fit cover the planted coefficients", "[evaluation][bootstrap]") {
  Simulation sim{12345};
  const auto [covered, total] = test::coverage_3x3(sim, 300, 200);
  const double rate = static_cast<double>(covered) / total;
  std::printf("bootstrap coverage (300 charts x 200 resamples, 9 coefficients): %.4f\n", rate);
  CHECK(rate > 0.92);
  CHECK(rate < 0.97);
}

// The predictions' ellipses (issue 47): widened as the coefficients' covariance (HC1), the 95 %
// ellipses on xy and a*b* hold the planted truth's colour in 93–97 % of cases: 150 charts × 24
// patches (3,600 ellipses per plane; patches of a chart share a fit, so the spread is wider than
// the binomial 0.4 %), 200 resamples each.
TEST_CASE("bootstrap: 95 % ellipses of the predicted xy and a*b* cover the planted truth", "[evaluation][bootstrap]") {
  Simulation sim{4242};
  const test::EllipseCoverage c = test::ellipse_coverage_3x3(sim, 150, 200);
  const double xy = static_cast<double>(c.xy) / c.total, ab = static_cast<double>(c.ab) / c.total;
  std::printf("bootstrap ellipse coverage (150 charts x 24 patches, 200 resamples): xy %.4f, a*b* %.4f\n", xy, ab);
  CHECK(xy > 0.93);
  CHECK(xy < 0.97);
  CHECK(ab > 0.93);
  CHECK(ab < 0.97);
}

TEST_CASE("bootstrap: same seed, same intervals, which bracket the fit, with covariance and ellipses", "[evaluation][bootstrap]") {
  const auto [rgb, xyz] = simulated_chart(7, 0.5);
  BootstrapOptions b = resampling(200);
  const ModelEvaluation ev = evaluate_model("matrix-3x3", rgb, xyz);
  b.loo_dE00 = ev.loo.patches.dE00;
  const BootstrapResult a = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b), c = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
  CHECK(a.resamples == 200);
  CHECK(a.failed == 0);
  CHECK((a.coefficients_lo - c.coefficients_lo).cwiseAbs().maxCoeff() == 0);
  CHECK(a.loo_dE00_mean.lo == c.loo_dE00_mean.lo);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      CHECK(a.coefficients_lo(i, j) < ev.fit.model.coefficients(i, j));
      CHECK(ev.fit.model.coefficients(i, j) < a.coefficients_hi(i, j));
    }
  REQUIRE(a.has_loo);
  CHECK(a.loo_dE00_mean.lo < ev.loo.dE00.mean);
  CHECK(ev.loo.dE00.mean < a.loo_dE00_mean.hi);
  CHECK(a.train_dE00_mean.lo < a.train_dE00_mean.hi);
  CHECK(a.covariance.rows() == 9);
  CHECK((a.covariance - a.covariance.transpose()).cwiseAbs().maxCoeff() < 1e-15);
  CHECK(a.covariance.diagonal().minCoeff() > 0);
  REQUIRE(a.predicted_XYZ_covariance.size() == 24);
  CHECK(a.predicted_XYZ_covariance[0].determinant() > 0);
  b.seed = 2;
  const BootstrapResult d = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
  CHECK((a.coefficients_lo - d.coefficients_lo).cwiseAbs().maxCoeff() > 0);
}

TEST_CASE("bootstrap: pixel statistics widen the intervals of a noiseless chart", "[evaluation][bootstrap]") {
  const auto [rgb, xyz] = simulated_chart(3, 0.0);  // XYZ = M·RGB exactly: resampling patches alone leaves no spread
  BootstrapOptions b = resampling(100);
  const BootstrapResult patches = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
  CHECK((patches.coefficients_hi - patches.coefficients_lo).cwiseAbs().maxCoeff() < 1e-12);
  b.pixel_std = PatchMatrix::Constant(24, 3, 4.0);
  b.pixel_count.assign(24, 400);
  const BootstrapResult pixels = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
  CHECK(pixels.pixels);
  CHECK((pixels.coefficients_hi - pixels.coefficients_lo).minCoeff() > 1e-4);
}

TEST_CASE("bootstrap: progress, cancellation and refusals", "[evaluation][bootstrap]") {
  const test::SimulatedChart chart = simulated_chart(5, 1.0);
  const PatchMatrix &rgb = chart.rgb, &xyz = chart.xyz;  // named references: the lambdas below capture them
  BootstrapOptions b = resampling(100);
  int calls = 0;
  b.progress = [&](int done, int total) {
    ++calls;
    CHECK(total == 100);
    return done < 40;
  };
  const BootstrapResult r = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
  CHECK(r.cancelled);
  CHECK(r.resamples == 40);
  CHECK(calls == 20);
  b.progress = nullptr;
  b.resamples = 0;
  require_code([&] { bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b); }, ErrorCode::InvalidArgument);
  b.resamples = 10;
  b.level = 1;
  require_code([&] { bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b); }, ErrorCode::InvalidArgument);
  b.level = 0.9;
  b.pixel_std = PatchMatrix::Constant(23, 3, 1.0);
  b.pixel_count.assign(23, 10);
  require_code([&] { bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b); }, ErrorCode::InvalidArgument);
}

TEST_CASE("bootstrap: a run stepped in chunks gives bootstrap_fit's result, with xy and a*b* ellipses", "[evaluation][bootstrap]") {
  const BootstrapOptions b = resampling(120, 0.9);
  const auto [rgb, xyz] = simulated_chart(11, 0.5);
  const BootstrapResult whole = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
  BootstrapRun run("matrix-3x3", rgb, xyz, FitOptions{}, b);
  CHECK(run.step(50) == 50);
  const BootstrapResult part = run.result();
  CHECK(part.cancelled);
  CHECK(part.resamples == 50);
  CHECK(run.step(7) == 57);
  CHECK(run.step(1000) == 120);
  const BootstrapResult chunked = run.result();
  CHECK_FALSE(chunked.cancelled);
  CHECK((whole.coefficients_lo - chunked.coefficients_lo).cwiseAbs().maxCoeff() == 0);
  CHECK((whole.covariance - chunked.covariance).cwiseAbs().maxCoeff() == 0);
  CHECK(whole.train_dE00_mean.hi == chunked.train_dE00_mean.hi);
  REQUIRE(chunked.predicted_xy_covariance.size() == 24);
  REQUIRE(chunked.predicted_ab_covariance.size() == 24);
  CHECK(chunked.predicted_xy_covariance[3] == whole.predicted_xy_covariance[3]);
  // k² = ν((1 − level)^(−2/ν) − 1), ν = 24 − 3 (F(2, 21) at 0.9: 2.575, so k² = 5.150 against χ²₂'s 4.605).
  CHECK(chunked.ellipse_scale == Approx(std::sqrt(21 * (std::pow(0.1, -2.0 / 21) - 1))).epsilon(1e-14));
  CHECK(chunked.ellipse_scale > std::sqrt(-2 * std::log(0.1)));
  // The xy covariance is the XYZ one carried through x = X/(X+Y+Z), y = Y/(X+Y+Z) to first order
  // (the spread is small): J Σ_XYZ Jᵀ.
  for (int i = 0; i < 24; i += 5) {
    const Vec3 v = predict(run.model(), rgb).row(i).transpose();
    const double s = v.sum();
    Eigen::Matrix<double, 2, 3> J;
    J << (s - v[0]) / (s * s), -v[0] / (s * s), -v[0] / (s * s), -v[1] / (s * s), (s - v[1]) / (s * s), -v[1] / (s * s);
    const Eigen::Matrix2d linear = J * chunked.predicted_XYZ_covariance[static_cast<size_t>(i)] * J.transpose();
    const Eigen::Matrix2d& c = chunked.predicted_xy_covariance[static_cast<size_t>(i)];
    CHECK(c.determinant() > 0);
    CHECK((c - linear).cwiseAbs().maxCoeff() < 0.05 * linear.cwiseAbs().maxCoeff());
  }
}

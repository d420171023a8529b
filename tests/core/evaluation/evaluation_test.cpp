// Evaluation: summaries, per-patch differences, NRMSE, leave-one-out, compare, transfer table.
#include <cmath>

#include "synthetic.hpp"
#include "test_support.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {
PatchMatrix rgb_grid(int n, unsigned seed) { return test::random_patches(n, seed, 0.03, 0.9); }
}  // namespace

TEST_CASE("summaries: min, median, mean, p95, max, RMS, std", "[evaluation]") {
  const Summary s = summarize({4, 1, 3, 2});
  CHECK(s.min == 1);
  CHECK(s.max == 4);
  CHECK(s.median == Approx(2.5));
  CHECK(s.mean == Approx(2.5));
  CHECK(s.p95 == Approx(3.85));  // numpy.percentile([1,2,3,4], 95)
  CHECK(s.rms == Approx(std::sqrt(7.5)));
  CHECK(s.std == Approx(std::sqrt(1.25)));
  CHECK(std::isnan(summarize({}).mean));
}

TEST_CASE("evaluate: identical data gives zero errors — NRMSE uses the reference range", "[evaluation]") {
  PatchMatrix ref = rgb_grid(10, 1) * 100.0;
  const Metrics z = evaluate(ref, ref);
  CHECK(z.dE00.max == 0);
  CHECK(z.dE_xyz.max == 0);
  PatchMatrix est = ref;
  est.col(1).array() += 2.0;  // Y off by 2 everywhere
  const Metrics m = evaluate(est, ref);
  const double range = ref.col(1).maxCoeff() - ref.col(1).minCoeff();
  CHECK(m.NRMSE[1] == Approx(2.0 / range));
  CHECK(m.NRMSE[0] == 0);
  CHECK(m.dE_xyz.mean == Approx(2.0));
  CHECK(m.patches.rel_Y[0] == Approx(2.0 / ref(0, 1)));
  CHECK(m.dE00.min > 0);
  // dL carries the lightness part: estimate lighter -> positive dL.
  CHECK(m.patches.dL[0] > 0);
}

TEST_CASE("leave-one-out is exact for a planted model and larger than training error on noise", "[evaluation]") {
  const PatchMatrix rgb = rgb_grid(24, 4);
  Model truth{"matrix-3x4", Eigen::MatrixXd(3, 4)};
  truth.coefficients << 40, 30, 15, 1, 20, 70, 8, 1.5, 2, 10, 90, 0.5;
  const PatchMatrix xyz = predict(truth, rgb);
  const PatchMatrix loo = leave_one_out("matrix-3x4", rgb, xyz);
  CHECK((loo - xyz).cwiseAbs().maxCoeff() < 1e-9);
  PatchMatrix noisy = xyz;
  std::mt19937 rng(3);
  std::normal_distribution<double> nd(0, 0.5);
  for (int i = 0; i < 24; ++i)
    for (int c = 0; c < 3; ++c) noisy(i, c) = std::max(0.0, noisy(i, c) + nd(rng));
  const ModelEvaluation ev = evaluate_model("Finlayson2015-3", rgb, noisy);
  REQUIRE(ev.has_loo);
  CHECK(ev.loo.dE00.mean > ev.training.dE00.mean);
}

TEST_CASE("compare: every model × objective, sorted by held-out error, refusals last", "[evaluation]") {
  const PatchMatrix rgb = rgb_grid(24, 8);
  Model truth{"Finlayson2015-2", Eigen::MatrixXd(3, 6)};
  truth.coefficients << 40, 30, 15, 3, 1, 2, 20, 70, 8, 1, 2, 1, 2, 10, 90, 1, 1, 3;
  const PatchMatrix xyz = predict(truth, rgb);
  const auto rows = compare_models(rgb, xyz, {}, {}, {Objective::LeastSquares});
  REQUIRE(rows.size() > 10);
  bool seen_refused = false;
  double last = -1;
  for (const auto& r : rows) {
    if (!r.ok) {
      seen_refused = true;
      CHECK(!r.error_code.empty());
      continue;
    }
    CHECK(!seen_refused);
    if (r.has_loo) {
      CHECK(r.loo_dE00.mean >= last);
      last = r.loo_dE00.mean;
    }
  }
  CHECK(seen_refused);  // Cheung2004-35 on 24 patches
  // The generating model (or a superset) is at the top with ~zero held-out error.
  CHECK(rows.front().loo_dE00.mean < 1e-6);
}

TEST_CASE("compare: the numbers do not depend on the thread count", "[evaluation]") {
  // Natively the rows are spread over threads (wasm: in order). One thread and three threads must
  // give the same rows in the same order, bit for bit.
  const PatchMatrix rgb = rgb_grid(24, 7);
  Model truth{"matrix-3x3", Eigen::Matrix3d()};
  truth.coefficients << 40, 30, 15, 20, 70, 8, 2, 10, 90;
  PatchMatrix xyz = predict(truth, rgb);
  for (Eigen::Index i = 0; i < xyz.rows(); ++i) xyz(i, static_cast<int>(i % 3)) *= 1.0 + 0.01 * static_cast<double>(i % 5);
  const std::vector<std::string> models = {"matrix-3x3", "matrix-3x4", "Finlayson2015-2", "Cheung2004-35"};
  const std::vector<Objective> objectives = {Objective::LeastSquares, Objective::PatternSearch, Objective::DeltaE2000};
  set_compare_threads(1);
  const auto one = compare_models(rgb, xyz, {}, models, objectives);
  set_compare_threads(3);
  const auto three = compare_models(rgb, xyz, {}, models, objectives);
  set_compare_threads(0);
  CHECK(compare_threads() == 0);
  REQUIRE(one.size() == 12);
  REQUIRE(three.size() == one.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    CHECK(one[k].model_id == three[k].model_id);
    CHECK(one[k].objective == three[k].objective);
    CHECK(one[k].ok == three[k].ok);
    CHECK(one[k].train_dE00.mean == three[k].train_dE00.mean);
    CHECK(one[k].loo_dE00.mean == three[k].loo_dE00.mean);
  }
  CHECK_THROWS_AS(set_compare_threads(-1), Error);
}

TEST_CASE("transfer table: train on one set, test on another (Abed 2013 Table IV layout)", "[evaluation]") {
  const PatchMatrix a = rgb_grid(24, 1), b = rgb_grid(40, 2), test = rgb_grid(10, 3);
  Model truth{"matrix-3x3", Eigen::Matrix3d()};
  truth.coefficients << 40, 30, 15, 20, 70, 8, 2, 10, 90;
  const auto cells = transfer_table({{"A", a, predict(truth, a)}, {"B", b, predict(truth, b)}}, test,
                                    predict(truth, test), {"matrix-3x3", "matrix-3x4"},
                                    {Objective::LeastSquares});
  REQUIRE(cells.size() == 4);
  for (const auto& c : cells) {
    CHECK(c.ok);
    CHECK(c.dE00.max < 1e-6);
  }
}

TEST_CASE("least-squares leave-one-out in closed form equals N refits", "[evaluation][loo]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.02, 1.0);
  std::normal_distribution<double> noise(0, 0.3);
  const int n = 30;
  PatchMatrix rgb(n, 3), xyz(n, 3);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) rgb(i, c) = 1000 * u(rng);
    xyz(i, 0) = 0.04 * rgb(i, 0) + 0.03 * rgb(i, 1) + 0.01 * rgb(i, 2) + std::sqrt(rgb(i, 0) * rgb(i, 1)) * 0.01 + 2 + noise(rng);
    xyz(i, 1) = 0.02 * rgb(i, 0) + 0.06 * rgb(i, 1) + 0.01 * rgb(i, 2) + 1 + noise(rng);
    xyz(i, 2) = 0.01 * rgb(i, 0) + 0.01 * rgb(i, 1) + 0.08 * rgb(i, 2) + 3 + noise(rng);
  }
  for (const char* id : {"matrix-3x3", "matrix-3x4", "Finlayson2015-2", "Shen2008", "Cheung2004-10"}) {
    for (int white : {-1, 7}) {
      FitOptions o;
      if (white >= 0) {
        o.preserve_white = true;
        o.white_RGB = rgb.row(white).transpose();
        o.white_XYZ = xyz.row(white).transpose();
      }
      const PatchMatrix closed = leave_one_out_least_squares(id, rgb, xyz, o, white);
      double worst = 0;
      int at = -1;
      for (int k = 0; k < n; ++k) {
        PatchMatrix r(n - 1, 3), x(n - 1, 3);
        for (int i = 0, j = 0; i < n; ++i)
          if (i != k) r.row(j) = rgb.row(i), x.row(j++) = xyz.row(i);
        FitOptions f = o;
        if (k == white) f.preserve_white = false;
        const Vec3 refit = predict(fit(id, r, x, f).model, Vec3(rgb.row(k).transpose()));
        const double d = (refit - Vec3(closed.row(k).transpose())).cwiseAbs().maxCoeff() / refit.cwiseAbs().maxCoeff();
        if (d > worst) worst = d, at = k;
      }
      INFO(id << (white >= 0 ? " with white" : "") << ": worst relative difference " << worst << " at patch " << at + 1
              << " (tolerance 1e-9)");
      CHECK(worst < 1e-9);
    }
  }
  // The folds a refit refuses are refused: a channel that only one patch makes vary.
  PatchMatrix flat = rgb;
  for (int i = 1; i < n; ++i) flat(i, 2) = 500;
  require_code([&] { leave_one_out_least_squares("matrix-3x4", flat, xyz); }, ErrorCode::IllConditioned);
}

TEST_CASE("quantile: Summary's rule for any q, non-finite values left out", "[evaluation]") {
  const std::vector<double> v = {7, 1, NAN, 4, 10, 2, INFINITY, 3};
  const Summary s = summarize(v);
  CHECK(quantile(v, 0.5) == s.median);
  CHECK(quantile(v, 0.95) == s.p95);
  CHECK(quantile(v, 0) == 1);
  CHECK(quantile(v, 1) == 10);
  CHECK(quantile(v, 0.25) == Approx(2.25));  // between the 2nd (2) and 3rd (3) of 6: numpy's 2.25
  CHECK(std::isnan(quantile({NAN}, 0.5)));
  require_code([] { quantile({1, 2}, 1.5); }, ErrorCode::InvalidArgument);
}

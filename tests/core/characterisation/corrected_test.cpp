// The corrected 3×3 of Abed, Berns & Masaoka 2013 (eqs 6-13, App. C eqs 26-28) as a model a user
// fits on their own patches: a planted solution, the simulated Table IV (the surface module's
// cells, an independent path through the same equations), leave-one-out and refusals.
#include <cmath>

#include "test_support.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/surface/geometry_table.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {
struct Planted {
  Mat3 A;
  Vec3 offset;
  PatchMatrix rgb, xyz;
  FitOptions options;
};
// XYZ = A·RGB + offset exactly (the flare/offset the 3×4 absorbs, eq 6); the white reference reads
// 1.05·A·RGB_w, so μ of eq (27) is 1.05.
Planted planted() {
  Planted p;
  p.A << 1.8, 0.6, 0.2, 0.2, 2.5, 0.1, 0.6, 0.4, 5.4;
  p.offset = Vec3(0.5, 0.8, 0.3);
  p.rgb.resize(24, 3);
  p.xyz.resize(24, 3);
  for (int i = 0; i < 24; ++i) {
    p.rgb.row(i) = Vec3(5 + (i * 7) % 29, 3 + (i * 11) % 31, 4 + (i * 13) % 27).transpose();
    p.xyz.row(i) = (p.A * p.rgb.row(i).transpose() + p.offset).transpose();
  }
  p.options.white_RGB = Vec3(40, 38, 15);
  p.options.white_XYZ = 1.05 * (p.A * p.options.white_RGB);
  p.options.preserve_white = true;  // what --white sets; the corrected 3×3 uses the pair for μ only
  return p;
}
}  // namespace

TEST_CASE("corrected-3x3: the planted 3x4 without offset, scaled by mu from the white (eqs 26-28)",
          "[characterisation][corrected]") {
  const Planted p = planted();
  const FitResult r = fit(kCorrected3x3, p.rgb, p.xyz, p.options);
  CHECK(r.model.id == kCorrected3x3);
  CHECK(r.mu == Approx(1.05).epsilon(1e-10));
  CHECK((r.model.coefficients - 1.05 * p.A).cwiseAbs().maxCoeff() < 1e-8);
  CHECK_FALSE(r.white_preserved);
  CHECK(r.status == FitStatus::Ok);
  // Predictions are those of a plain 3×3 with the same coefficients (the model's span is matrix-3x3's).
  Model plain{"matrix-3x3", r.model.coefficients};
  CHECK((predict(r.model, p.rgb) - predict(plain, p.rgb)).cwiseAbs().maxCoeff() == 0);
  CHECK((r.fitted - (p.rgb * (1.05 * p.A).transpose())).cwiseAbs().maxCoeff() < 1e-7);
  CHECK(model_info(kCorrected3x3).duplicate_of == "matrix-3x3");
  CHECK(model_info(kCorrected3x3).linear);
}

TEST_CASE("corrected-3x3: refusals", "[characterisation][corrected]") {
  Planted p = planted();
  FitOptions o = p.options;
  o.objective = Objective::PatternSearch;
  require_code([&] { fit(kCorrected3x3, p.rgb, p.xyz, o); }, ErrorCode::InvalidArgument);
  o = p.options;
  o.white_RGB = Vec3::Zero();
  require_code([&] { fit(kCorrected3x3, p.rgb, p.xyz, o); }, ErrorCode::InvalidArgument);
  require_code([&] { fit(kCorrected3x3, p.rgb.topRows(3), p.xyz.topRows(3), p.options); }, ErrorCode::TooFewPatches);
  require_code([&] { leave_one_out_least_squares(kCorrected3x3, p.rgb, p.xyz, p.options); }, ErrorCode::InvalidArgument);
}

TEST_CASE("corrected-3x3: leave-one-out refits each fold, keeping the white reference", "[characterisation][corrected]") {
  Planted p = planted();
  for (int i = 0; i < 24; ++i) p.xyz(i, (i % 3)) += 0.2 * ((i * 5) % 7 - 3);  // residuals, so folds differ
  const int white = 3;
  const ModelEvaluation ev = evaluate_model(kCorrected3x3, p.rgb, p.xyz, p.options, white);
  REQUIRE(ev.has_loo);
  for (Eigen::Index k = 0; k < 24; ++k) {
    PatchMatrix r(23, 3), x(23, 3);
    for (Eigen::Index i = 0, j = 0; i < 24; ++i)
      if (i != k) r.row(j) = p.rgb.row(i), x.row(j++) = p.xyz.row(i);
    const FitResult f = fit(kCorrected3x3, r, x, p.options);
    INFO("fold " << k);
    CHECK((ev.loo_XYZ.row(k) - predict(f.model, Vec3(p.rgb.row(k).transpose())).transpose()).cwiseAbs().maxCoeff() == 0);
  }
  CHECK(ev.loo.dE00.mean > ev.training.dE00.mean);
}

// Independent check: the simulated Table IV (surface/geometry_table.hpp) computes its
// corrected-3x3 column with fit_corrected_3x3_Abed2013 directly from the instrument's XYZ and the
// PTFE white. The user's path (fit by model id) gives the same matrix, μ and test-chart figures.
TEST_CASE("corrected-3x3: the user's fit reproduces the simulated Table IV column", "[characterisation][corrected][table4]") {
  const GeometryExperiment x = geometry_experiment_Abed2013();
  const auto cells = geometry_table_Abed2013(x.training, x.test, x.options);
  const SpectralData D50 = illuminant_spd("D50");
  const Vec3 white = illuminant_white_XYZ(D50, x.options.observer);
  int checked = 0;
  for (const auto& chart : x.training) {
    const std::vector<Vec3> v = reflectances_to_XYZ(chart.measured, D50, x.options.observer);
    PatchMatrix instrument(static_cast<Eigen::Index>(v.size()), 3);
    for (size_t i = 0; i < v.size(); ++i) instrument.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
    FitOptions o;
    o.white_RGB = x.options.white_RGB;
    o.white_XYZ = x.options.white_reflectance * white;
    const FitResult r = fit(kCorrected3x3, chart.camera_RGB, instrument, o);
    for (const auto& c : cells) {
      if (c.training != chart.name || c.method != kCorrected3x3) continue;
      INFO(chart.name << ": mu " << r.mu << " vs " << c.mu);
      REQUIRE(c.ok);
      CHECK(r.mu == c.mu);
      CHECK((r.model.coefficients - c.matrix).cwiseAbs().maxCoeff() == 0);
      const Metrics m = evaluate(predict(r.model, x.test.camera_RGB) / 100.0, x.test.seen_XYZ / 100.0, white / 100.0);
      CHECK(m.dE00.mean == Approx(c.dE00.mean).epsilon(1e-12));
      // μ lies near the white's reflectance ratio (the offset the 3×4 absorbed is small): a sanity bound.
      CHECK(c.mu > 0.8);
      CHECK(c.mu < 1.25);
      ++checked;
    }
  }
  CHECK(checked == static_cast<int>(x.training.size()));
}

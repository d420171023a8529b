// The lab's exercise 2 (why a 3×3 is not enough): the Luther camera needs nothing more than a
// 3×3; a real camera's 22-term polynomial on 24 noisy patches fits them better and everything
// else far worse; 35 terms on 24 patches is refused.
#include <cmath>

#include "test_support.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {
const OverfitRow& row(const std::vector<OverfitRow>& rows, const std::string& model, const std::string& chart) {
  for (const auto& r : rows)
    if (r.model == model && r.training == chart) return r;
  FAIL("no row " << model << " on " << chart);
  return rows.front();
}
}  // namespace

TEST_CASE("lab overfit: the Luther camera is exact with a 3x3, everywhere", "[lab]") {
  OverfitOptions o;
  o.noise = 0;
  o.models = {"matrix-3x3"};
  for (const auto& r : lab_overfit_exercise(cmf_sensitivities(), illuminant_spd("D65"), o)) {
    INFO(r.training);
    REQUIRE(r.ok);
    // Not 0: the camera sums on its 5 nm grid, the reference XYZ at 1 nm (CIE 15).
    CHECK(r.train_dE00 < 0.01);
    CHECK(r.loo_dE00 < 0.01);
    CHECK(r.test_dE00 < 0.01);
  }
}

TEST_CASE("lab overfit: 22 terms on 24 noisy patches fit them and miss the rest, 35 terms are refused", "[lab]") {
  const auto rows = lab_overfit_exercise(camera_ssf("Canon_EOS_5D_Mark_II"), illuminant_spd("D65"));
  REQUIRE(rows.size() == 10);
  const OverfitRow &m3 = row(rows, "matrix-3x3", "cc24"), &p22 = row(rows, "Cheung2004-22", "cc24");
  REQUIRE(m3.ok);
  REQUIRE(p22.ok);
  INFO("3x3 " << m3.train_dE00 << "/" << m3.loo_dE00 << "/" << m3.test_dE00 << ", 22 terms " << p22.train_dE00 << "/"
              << p22.loo_dE00 << "/" << p22.test_dE00);
  CHECK(p22.train_dE00 < 0.5 * m3.train_dE00);
  CHECK(p22.loo_dE00 > 2 * m3.loo_dE00);
  CHECK(p22.test_dE00 > 3 * m3.test_dE00);
  // A real camera is not a Luther camera: the 3x3 leaves visible errors.
  CHECK(m3.train_dE00 > 0.5);
  const OverfitRow& p35 = row(rows, "Cheung2004-35", "cc24");
  CHECK_FALSE(p35.ok);
  CHECK(p35.error_code == "TOO_FEW_PATCHES");
  // With 140 patches the same 35 terms fit, and the held-out error stays moderate.
  const OverfitRow& sg35 = row(rows, "Cheung2004-35", "sg140");
  REQUIRE(sg35.ok);
  CHECK(sg35.test_dE00 < 2);
  OverfitOptions bad;
  bad.models = {"matrix-9x9"};
  test::require_code([&] { lab_overfit_exercise(cmf_sensitivities(), illuminant_spd("D65"), bad); }, ErrorCode::UnknownId);
}

TEST_CASE("lab spectra to colour: a patch's XYZ and Lab per illuminant and observer are the reference step's", "[lab]") {
  const SpectraToColour e = lab_spectra_to_colour("cc24", "c3");
  CHECK(e.patch == "C3");
  REQUIRE(e.rows.size() == 6);
  REQUIRE(e.stimulus.size() == 3);
  for (const auto& r : e.rows) {
    const ReferenceChart ref = reference_chart("cc24", r.illuminant, parse_observer(r.observer));
    size_t k = 0;
    while (k < ref.ids.size() && ref.ids[k] != "C3") ++k;
    REQUIRE(k < ref.ids.size());
    INFO(r.illuminant << " " << r.observer);
    CHECK((r.XYZ - ref.XYZ[k]).norm() == 0);
    CHECK(r.x == Approx(r.XYZ[0] / r.XYZ.sum()));
  }
  // C3 is the red patch: red under every light once CIELAB normalises to the light's white, and
  // its chromaticity moves towards the illuminant's (A's x is larger than D65's).
  for (const auto& r : e.rows) CHECK(r.Lab[1] > 30);
  CHECK(e.rows[2].x > e.rows[0].x);
  test::require_code([] { lab_spectra_to_colour("cc24", "Z9"); }, ErrorCode::UnknownId);
}

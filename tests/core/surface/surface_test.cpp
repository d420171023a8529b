// The surface-correction table: rows, options, the `spectral` text, coded errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "test_support.hpp"
#include "tristim/surface/saunderson.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;

namespace {

SpectralData two_patches() {
  SpectralData d;
  d.wavelengths = {400, 500, 600, 700};
  d.names = {"A1", "A2"};
  d.values = {{0.05, 0.06, 0.07, 0.08}, {0.80, 0.85, 0.88, 0.9}};
  return d;
}

}  // namespace

TEST_CASE("surface table lists none, scaler, offset, scaler-offset, saunderson", "[surface]") {
  std::vector<std::string> ids;
  for (const auto& m : surface_table()) ids.push_back(m.info.id);
  CHECK(ids == std::vector<std::string>{"none", "scaler", "offset", "scaler-offset", "saunderson"});
  for (const auto& m : surface_table())
    for (const auto& c : m.coefficients) {
      bool found = false;
      for (const auto& o : m.info.options) found = found || o.name == c;
      INFO(m.info.id << " " << c);
      CHECK(found);
    }
  test::require_code([] { surface_method("kubelka"); }, ErrorCode::UnknownId);
}

TEST_CASE("defaults are the identity", "[surface]") {
  const SpectralData d = two_patches();
  for (const auto& m : surface_table()) {
    const SpectralData out = correct_surface({m.info.id, {}, {}}, d);
    for (size_t k = 0; k < d.size(); ++k)
      for (size_t w = 0; w < d.wavelengths.size(); ++w) CHECK(out.values[k][w] == Approx(d.values[k][w]).margin(1e-15));
  }
}

TEST_CASE("rows apply their equations", "[surface]") {
  const SpectralData d = two_patches();
  const SpectralData so = correct_surface(parse_choice("scaler-offset:mu=1.1,rho=-0.02"), d);
  CHECK(so.values[1][2] == Approx(1.1 * 0.88 - 0.02).epsilon(1e-15));
  const SpectralData sc = correct_surface(parse_choice("scaler:mu=0.9"), d);
  CHECK(sc.values[0][0] == Approx(0.045).epsilon(1e-15));
  const SpectralData of = correct_surface(parse_choice("offset:rho=0.01"), d);
  CHECK(of.values[0][3] == Approx(0.09).epsilon(1e-15));
  const MethodChoice s = parse_choice("saunderson:k1=0.092,k2=0.6,k_ins=1,k1_capture=0.04,k2_capture=0.55,k_ins_capture=0");
  const SpectralData sa = correct_surface(s, d);
  CHECK(sa.values[1][1] ==
        Approx(saunderson_convert_Abed2013(0.85, {0.092, 0.6, 1}, {0.04, 0.55, 0})).epsilon(1e-13));
}

TEST_CASE("per-wavelength coefficients: interpolated, held outside, round trip", "[surface]") {
  const SpectralData d = two_patches();
  const MethodChoice c = parse_choice("scaler-offset:spectral=450/1/0;650/1.2/-0.01");
  const SpectralData out = correct_surface(c, d);
  CHECK(out.values[0][0] == Approx(0.05).epsilon(1e-15));                     // 400: held at 450's
  CHECK(out.values[0][1] == Approx(1.05 * 0.06 - 0.0025).epsilon(1e-14));     // 500: a quarter of the way
  CHECK(out.values[0][3] == Approx(1.2 * 0.08 - 0.01).epsilon(1e-14));        // 700: held at 650's
  const std::vector<double> grid = {400, 410.5, 700};
  const std::vector<std::vector<double>> coef = {{1.0123456789, -0.0123}, {0.5, 0.1}, {1.9, -0.4}};
  const std::string text = spectral_coefficients_text(grid, coef);
  MethodChoice back = surface_choice("scaler-offset", {1, 0});
  back.settings["spectral"] = text;
  CHECK(surface_coefficients(back, grid) == coef);
  // The CLI text of a choice reads back to the same choice.
  const MethodChoice full = surface_choice("saunderson", {0.092, 0.6, 1, 0.04, 0.55, 0.1234567890123});
  const MethodChoice again = complete_choice(surface_method("saunderson").info, parse_choice(surface_choice_text(full)));
  CHECK(again.parameters == full.parameters);
  CHECK(surface_choice_text(full).find("k1=0.092,") != std::string::npos);
}

TEST_CASE("bad coefficients and reflectances are coded", "[surface]") {
  const SpectralData d = two_patches();
  test::require_code([&] { correct_surface(parse_choice("saunderson:k1=1.2"), d); }, ErrorCode::InvalidArgument);
  test::require_code([&] { correct_surface(parse_choice("saunderson:k_ins=-0.1"), d); }, ErrorCode::InvalidArgument);
  test::require_code([&] { correct_surface(parse_choice("scaler:mu=3"), d); }, ErrorCode::InvalidArgument);
  test::require_code([&] { correct_surface(parse_choice("scaler:kappa=1"), d); }, ErrorCode::UnknownId);
  test::require_code([&] { correct_surface(parse_choice("scaler:spectral=400/1/2"), d); }, ErrorCode::InvalidArgument);
  test::require_code([&] { correct_surface(parse_choice("scaler:spectral=400/5"), d); }, ErrorCode::InvalidArgument);
  test::require_code([&] { correct_surface(parse_choice("scaler:spectral=500/1;400/1"), d); }, ErrorCode::NonMonotonic);
  SpectralData high = d, negative = d;
  high.values[1][0] = 1.6;
  negative.values[0][2] = -0.01;
  test::require_code([&] { correct_surface({"none", {}, {}}, high); }, ErrorCode::InvalidArgument);
  test::require_code([&] { correct_surface({"offset", {}, {}}, negative); }, ErrorCode::NegativeValue);
}

TEST_CASE("catalog: surface rows carry their equation, and Saunderson the options each geometry sets", "[surface][catalog]") {
  for (const SurfaceMethod& m : surface_table()) {
    INFO(m.info.id);
    CHECK(m.equation.empty() == m.coefficients.empty());
    for (const auto& [role, fields] : m.geometry) {
      CHECK((role == "measurement" || role == "capture"));
      CHECK(fields.size() == 3);
      for (const auto& [field, option] : fields) {
        CHECK((field == "k1" || field == "k2" || field == "k_ins"));
        CHECK(std::find(m.coefficients.begin(), m.coefficients.end(), option) != m.coefficients.end());
      }
    }
  }
  // A preset in the capture role sets the capture coefficients: the correction is eq (3) with it.
  const SurfaceMethod& s = surface_method("saunderson");
  const SaundersonGeometry meas = saunderson_preset("d8-sci").geometry, cap = saunderson_preset("t3-sg-diffuse").geometry;
  MethodChoice c{"saunderson", {}, {}};
  const auto set = [&](const std::string& role, const SaundersonGeometry& g) {
    const std::map<std::string, double> value = {{"k1", g.k1}, {"k2", g.k2}, {"k_ins", g.k_ins}};
    for (const auto& [field, option] : s.geometry.at(role)) c.parameters[option] = value.at(field);
  };
  set("measurement", meas);
  set("capture", cap);
  const SpectralData out = correct_surface(c, two_patches());
  CHECK(out.values[1][2] == Approx(saunderson_convert_Abed2013(0.88, meas, cap)).epsilon(1e-12));
}

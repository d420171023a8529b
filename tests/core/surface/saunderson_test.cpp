// Saunderson equations (Abed, Berns & Masaoka 2013 eqs 1-5, Appendices A-B): identities on grids
// of reflectances and coefficients, stated tolerances.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <utility>

#include "test_support.hpp"
#include "tristim/surface/saunderson.hpp"

using namespace tristim;

namespace {

// Random geometries with every coefficient in [0, 0.9] (k_ins in [0, 1]).
SaundersonGeometry random_geometry(std::mt19937& rng) {
  std::uniform_real_distribution<double> k(0, 0.9), ins(0, 1);
  return {k(rng), k(rng), ins(rng)};
}

// The worst relative difference |value - truth| / max(1, |truth|) over `trials` random pairs of
// geometries (measurement m, capture c, drawn by mt19937(seed)) and R = 0, 0.05, …, 1, where
// make(m, c) gives the function R -> {value, truth}. R whose truth is not finite or larger than
// `limit` in size are passed over.
template <class Make>
double worst_relative_difference(unsigned seed, int trials, double limit, Make make) {
  std::mt19937 rng(seed);
  double worst = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const SaundersonGeometry m = random_geometry(rng), c = random_geometry(rng);
    const auto value_and_truth = make(m, c);
    for (int i = 0; i <= 20; ++i) {
      const auto [value, truth] = value_and_truth(0.05 * i);
      if (!std::isfinite(truth) || std::fabs(truth) > limit) continue;
      worst = std::max(worst, std::fabs(value - truth) / std::max(1.0, std::fabs(truth)));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("eq (1) after eq (2) is the identity on a grid", "[surface][saunderson]") {
  double worst = 0;
  for (double k1 : {0.0, 0.04, 0.092, 0.3})
    for (double k2 : {0.0, 0.4, 0.6, 0.9})
      for (double kins : {0.0, 0.5, 1.0})
        for (int i = 0; i <= 100; ++i) {
          const SaundersonGeometry g{k1, k2, kins};
          const double R = 0.01 * i;
          worst = std::max(worst, std::fabs(saunderson_measured_Abed2013(saunderson_internal_Abed2013(R, g), g) - R));
          worst = std::max(worst, std::fabs(saunderson_internal_Abed2013(saunderson_measured_Abed2013(R, g), g) - R));
        }
  INFO("worst |eq1(eq2(R)) - R| = " << worst);
  CHECK(worst < 1e-13);
}

TEST_CASE("eq (1) matches hand values", "[surface][saunderson]") {
  // R_i = 0.5, k1 = 0.04, k2 = 0.6, k_ins = 0: 0.96 * 0.4 * 0.5 / 0.7 = 0.274285714...
  CHECK(saunderson_measured_Abed2013(0.5, {0.04, 0.6, 0}) == Approx(0.96 * 0.4 * 0.5 / 0.7).epsilon(1e-15));
  // A perfect internal reflector reads 1 - k1 (1 - k_ins): all of it with the specular included.
  CHECK(saunderson_measured_Abed2013(1.0, {0.092, 0.6, 1}) == Approx(1.0).epsilon(1e-15));
  CHECK(saunderson_measured_Abed2013(1.0, {0.092, 0.6, 0}) == Approx(1 - 0.092).epsilon(1e-15));
  // R_i = 0 reads the specular part alone.
  CHECK(saunderson_measured_Abed2013(0.0, {0.092, 0.6, 1}) == Approx(0.092).epsilon(1e-15));
}

TEST_CASE("eq (3) equals eq (2) then eq (1) for random coefficients", "[surface][saunderson]") {
  const double worst = worst_relative_difference(3, 500, INFINITY, [](const SaundersonGeometry& m, const SaundersonGeometry& c) {
    return [m, c](double R) {
      const double two_step = saunderson_measured_Abed2013(saunderson_internal_Abed2013(R, m), c);
      return std::pair{saunderson_convert_Abed2013(R, m, c), two_step};
    };
  });
  INFO("worst relative difference " << worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("eq (4) with the Appendix A mapping equals eq (3) for any six coefficients", "[surface][saunderson]") {
  const double worst = worst_relative_difference(4, 2000, 1e6, [](const SaundersonGeometry& m, const SaundersonGeometry& c) {
    const ThreeParameter t = three_parameter_Abed2013(m, c);
    return [m, c, t](double R) { return std::pair{t.apply(R), saunderson_convert_Abed2013(R, m, c)}; };
  });
  INFO("worst relative difference " << worst);
  CHECK(worst < 1e-10);
}

TEST_CASE("eq (5) is eq (3) with k2 = k2' (Appendix B)", "[surface][saunderson]") {
  std::mt19937 rng(5);
  double worst = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const SaundersonGeometry m = random_geometry(rng);
    SaundersonGeometry c = random_geometry(rng);
    c.k2 = m.k2;
    const ScalerOffset so = scaler_offset_Abed2013(m, c);
    // Appendix B's μ and ρ, written out.
    CHECK(so.mu == Approx((1 - c.k1) / (1 - m.k1)).epsilon(1e-14));
    CHECK(so.rho == Approx(c.k_ins * c.k1 - (1 - c.k1) / (1 - m.k1) * m.k_ins * m.k1).margin(1e-14));
    for (int i = 0; i <= 20; ++i) {
      const double R = 0.05 * i;
      worst = std::max(worst, std::fabs(so.apply(R) - saunderson_convert_Abed2013(R, m, c)));
    }
    // ... and eq (4) is then linear: β = 0.
    CHECK(std::fabs(three_parameter_Abed2013(m, c).beta) < 1e-14);
  }
  INFO("worst |eq5 - eq3| " << worst);
  CHECK(worst < 1e-13);
}

TEST_CASE("same geometry both ways is the identity", "[surface][saunderson]") {
  const SaundersonGeometry g{0.092, 0.6, 1};
  const ThreeParameter t = three_parameter_Abed2013(g, g);
  CHECK(t.alpha == Approx(0).margin(1e-15));
  CHECK(t.beta == Approx(0).margin(1e-15));
  CHECK(t.gamma == Approx(1).epsilon(1e-15));
  for (double R : {0.0, 0.3, 0.95}) CHECK(saunderson_convert_Abed2013(R, g, g) == Approx(R).margin(1e-15));
}

TEST_CASE("SCI to 45:0 lowers dark patches by about k1, barely changes the white", "[surface][saunderson]") {
  const SaundersonGeometry sci = saunderson_preset("d8-sci").geometry, o45 = saunderson_preset("45-0").geometry;
  const double black = saunderson_convert_Abed2013(0.10, sci, o45);
  const double white = saunderson_convert_Abed2013(0.90, sci, o45);
  CHECK(black < 0.10 - 0.05);
  CHECK(std::fabs(white - 0.90) < 0.05);
}

TEST_CASE("singular capture geometry and unknown preset are coded", "[surface][saunderson]") {
  // k1c = k2c = 1: every patch would read the same.
  test::require_code([] { three_parameter_Abed2013({0.04, 0.6, 0}, {1, 1, 0}); }, ErrorCode::IllPosed);
  test::require_code([] { saunderson_preset("d0-x"); }, ErrorCode::UnknownId);
  for (const auto& p : saunderson_presets()) {
    INFO(p.id);
    CHECK(!p.source.empty());
    CHECK(p.geometry.k1 >= 0);
    CHECK(p.geometry.k1 < 1);
    CHECK(p.geometry.k_ins <= 1);
  }
}

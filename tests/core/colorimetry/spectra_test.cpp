#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/colorimetry/spectra.hpp"

using namespace tristim;

namespace {

/// Every number inside the JSON bracket that follows the first occurrence of `anchor` (after
/// `then`, if given): enough to read colour-science's expectation files without a JSON library.
std::vector<double> json_numbers_after(const std::string& text, const std::string& anchor, const std::string& then = "") {
  size_t p = text.find(anchor);
  REQUIRE(p != std::string::npos);
  if (!then.empty()) {
    p = text.find(then, p);
    REQUIRE(p != std::string::npos);
  }
  p = text.find('[', p);
  int depth = 0;
  size_t end = p;
  for (; end < text.size(); ++end) {
    if (text[end] == '[') ++depth;
    if (text[end] == ']' && --depth == 0) break;
  }
  std::vector<double> out;
  const char* s = text.c_str() + p;
  const char* e = text.c_str() + end;
  while (s < e) {
    if (std::isdigit(static_cast<unsigned char>(*s)) || *s == '-' || *s == '.') {
      char* next = nullptr;
      out.push_back(std::strtod(s, &next));
      s = next;
    } else {
      ++s;
    }
  }
  return out;
}

const std::string kExpect = "tests/data/colour-science/colour_test_tristimulus_values_expected.json";

}  // namespace

TEST_CASE("Sprague interpolation is exact for a quartic and passes through the samples", "[spectra]") {
  auto f = [](double x) { return -3e-9 * std::pow(x - 520, 4) + 1e-6 * x * x + 0.3; };
  const auto w = wavelength_grid(380, 730, 10);
  std::vector<double> v;
  for (double x : w) v.push_back(f(x));
  const auto fine = wavelength_grid(380, 730, 1);
  const auto got = interpolate_spectrum(w, v, fine);
  double worst = 0;
  // Away from the two end intervals on each side (there the CIE 167 boundary points, which are
  // not polynomial extrapolation, take part; the colour-science test below covers them).
  for (size_t i = 0; i < fine.size(); ++i)
    if (fine[i] >= 400 && fine[i] <= 710) worst = std::max(worst, std::abs(got[i] - f(fine[i])));
  INFO("worst |Sprague - quartic| = " << worst);
  CHECK(worst < 1e-12);  // Sprague reproduces polynomials up to degree 4
  for (size_t i = 0; i < w.size(); ++i) CHECK(got[static_cast<size_t>((w[i] - 380))] == v[i]);
}

TEST_CASE("non-uniform data are interpolated linearly and extrapolation holds the end values", "[spectra]") {
  const std::vector<double> w = {400, 410, 430, 460};
  const std::vector<double> v = {1, 2, 4, 1};
  const auto got = interpolate_spectrum(w, v, {350, 400, 405, 420, 445, 460, 800});
  const std::vector<double> want = {1, 1, 1.5, 3, 2.5, 1, 1};
  for (size_t i = 0; i < want.size(); ++i) CHECK(got[i] == Approx(want[i]).margin(1e-15));
  // Uniform but fewer than 6 samples: linear too.
  const auto lin = interpolate_spectrum({400, 500, 600}, {0, 1, 0}, {450, 550});
  CHECK(lin[0] == Approx(0.5));
  CHECK(lin[1] == Approx(0.5));
  tristim::test::require_code([&] { interpolate_spectrum({400, 400, 500}, {1, 2, 3}, {450}); }, ErrorCode::NonMonotonic);
}

// colour-science: msds_to_XYZ_integration(MSDS_TWO, CIE 1931 2°, SDS_ILLUMINANTS['D65']). The 12
// test spectra have 6 samples 400..700 nm at 60 nm, so this exercises Sprague with its boundary
// rule, constant extrapolation from 400/700 nm to 360/830 nm, D65 (300-780 nm, 5 nm) interpolated
// *linearly* to 1 nm (CIE 15 for D illuminants; with Sprague the Z values differ by 2e-4 relative,
// so this test pins the rule down) and held from 780 to 830 nm, and the 1 nm summation. Same rule, same data, so only
// floating-point summation order separates us: tolerance 1e-7 (colour's own atol).
TEST_CASE("XYZ of colour-science's MSDS_TWO under D65 matches colour's integration to 1e-7", "[spectra][colour]") {
  const std::string json = test::read_test_file(kExpect);
  const auto data = json_numbers_after(json, "\"DATA_TWO\"");
  const auto expected = json_numbers_after(json, "\"TVS_D65_INTEGRATION_MSDS\"");
  REQUIRE(data.size() == 72);
  REQUIRE(expected.size() == 36);
  SpectralData msds;
  msds.wavelengths = wavelength_grid(400, 700, 60);
  for (int s = 0; s < 12; ++s) {
    msds.values.emplace_back(data.begin() + 6 * s, data.begin() + 6 * s + 6);
    msds.names.push_back(std::to_string(s));
  }
  const auto XYZ = reflectances_to_XYZ(msds, illuminant_spd("D65"), Observer::CIE1931_2);
  double worst = 0;
  for (int s = 0; s < 12; ++s)
    for (int k = 0; k < 3; ++k) {
      const double d = std::abs(XYZ[s][k] - expected[3 * s + k]);
      if (d > worst) {
        worst = d;
        UNSCOPED_INFO("worst so far: spectrum " << s << " component " << k << ": got " << XYZ[s][k] << ", colour "
                                                << expected[3 * s + k]);
      }
    }
  INFO("worst |ours - colour| = " << worst);
  CHECK(worst < 1e-7);
}

// colour-science: sd_to_XYZ(BabelColor average) with its defaults, which are illuminant E and the
// *ASTM E308* method (tristimulus weighting factors for the 10 nm data) with the CMFs trimmed to 360-780 nm.
// We integrate at 1 nm after Sprague interpolation instead (our one rule), so the two differ by the
// method, not by a bug: on these smooth 10 nm reflectances the two differ by at most 3.7e-4 in
// XYZ (0..100). Tolerance 2e-3 (far below any visible difference, well above rounding).
TEST_CASE("ColorChecker BabelColor average under E matches colour's sd_to_XYZ within 2e-3", "[spectra][colour]") {
  const std::string json = test::read_test_file(kExpect);
  const auto expected = json_numbers_after(json, "SDS_COLOURCHECKERS['babel_average']", "\"expected\"");
  REQUIRE(expected.size() == 72);
  const PatchTable babel = read_patch_file(
      test::read_test_file("tests/data/colour-science/colorchecker24_babelcolor_average_reflectance_380-730_10nm.csv"), "babel.csv");
  REQUIRE(babel.spectra.size() == 24);
  const auto XYZ = reflectances_to_XYZ(babel.spectra, illuminant_spd("E"), Observer::CIE1931_2);
  double worst = 0;
  for (int s = 0; s < 24; ++s)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(XYZ[s][k] - expected[3 * s + k]));
  INFO("worst |integration - colour ASTM E308| = " << worst);
  CHECK(worst < 2e-3);
}

// CIE 15:2004 Table T.3 white points (Y = 100), tabulated from 5 nm summation; we integrate at
// 1 nm after linear interpolation of the 5 nm SPD, which moves X and Z by up to 0.025 (D75 10° Z);
// tolerance 0.03 (0.03 % of the white: invisible, but a wrong table or rule shows at > 0.1).
TEST_CASE("white points of the built-in illuminants match CIE 15:2004 Table T.3 within 0.03", "[spectra]") {
  struct W {
    const char* id;
    Observer obs;
    double X, Z;
  };
  const W table[] = {{"A", Observer::CIE1931_2, 109.850, 35.585},   {"D50", Observer::CIE1931_2, 96.422, 82.521},
                     {"D55", Observer::CIE1931_2, 95.682, 92.149},  {"D65", Observer::CIE1931_2, 95.047, 108.883},
                     {"D75", Observer::CIE1931_2, 94.972, 122.638}, {"A", Observer::CIE1964_10, 111.144, 35.200},
                     {"D50", Observer::CIE1964_10, 96.720, 81.427}, {"D55", Observer::CIE1964_10, 95.799, 90.926},
                     {"D65", Observer::CIE1964_10, 94.811, 107.304}, {"D75", Observer::CIE1964_10, 94.416, 120.641}};
  for (const auto& w : table) {
    const Vec3 white = illuminant_white_XYZ(illuminant_spd(w.id), w.obs);
    INFO(w.id << " " << observer_name(w.obs) << ": " << white.transpose());
    CHECK(white[1] == Approx(100).margin(1e-9));
    CHECK(std::abs(white[0] - w.X) < 0.03);
    CHECK(std::abs(white[2] - w.Z) < 0.03);
  }
  // E: equal energy -> X = Y = Z to the CMF normalisation (CIE: 100, 100, 100 within 0.1).
  const Vec3 E = illuminant_white_XYZ(illuminant_spd("E"));
  CHECK(std::abs(E[0] - 100) < 0.1);
  CHECK(std::abs(E[2] - 100) < 0.1);
}

// CIE 15:2004: the tabulated D65 was computed from S0, S1, S2 at the nominal CCT 6504 K with M1,
// M2 rounded to 3 decimals. The table has 4-6 significant figures (e.g. 117.812), so the rebuilt
// SPD must match to the table's last digit (3 decimals): we see <= 0.00085; tolerance 1e-3.
TEST_CASE("D65 (and D50, D55, D75) rebuilt from S0, S1, S2 match the tables", "[spectra]") {
  const double c2_ratio = 1.4388 / 1.4380;
  for (auto [id, T] : std::vector<std::pair<std::string, double>>{{"D65", 6500}, {"D50", 5000}, {"D55", 5500}, {"D75", 7500}}) {
    const SpectralData table = illuminant_spd(id);
    const SpectralData rebuilt = daylight_spd(T * c2_ratio);
    double worst = 0, at = 0;
    for (size_t i = 0; i < table.wavelengths.size(); ++i) {
      const auto j = static_cast<size_t>(std::lround((table.wavelengths[i] - rebuilt.wavelengths[0]) / 5.0));
      REQUIRE(rebuilt.wavelengths[j] == table.wavelengths[i]);
      const double d = std::abs(rebuilt.values[0][j] - table.values[0][i]);
      if (d > worst) {
        worst = d;
        at = table.wavelengths[i];
      }
    }
    INFO(id << ": worst |S0/S1/S2 - table| = " << worst << " at " << at << " nm");
    CHECK(worst < 1e-3);
  }
  // The id "D6504" reaches the same SPD through illuminant_spd.
  CHECK(illuminant_spd("D6504").values[0].size() == daylight_spd(6504).values[0].size());
}

TEST_CASE("spectral locus and observer ids", "[spectra]") {
  const SpectralLocus l = spectral_locus(Observer::CIE1931_2);
  REQUIRE(l.wavelengths.size() == 471);
  // 520 nm on the CIE 1931 locus: x = 0.07430, y = 0.83380 (CIE 15 Table T.? / colour).
  const size_t i520 = 160;
  CHECK(l.wavelengths[i520] == 520);
  CHECK(l.x[i520] == Approx(0.0743).margin(2e-4));
  CHECK(l.y[i520] == Approx(0.8338).margin(2e-4));
  CHECK(parse_observer("1964") == Observer::CIE1964_10);
  CHECK(parse_observer("2") == Observer::CIE1931_2);
  tristim::test::require_code([&] { parse_observer("1976"); }, ErrorCode::UnknownId);
  tristim::test::require_code([&] { illuminant_spd("D42"); }, ErrorCode::UnknownId);
}

namespace {

/// The per-column formula reflectances_to_XYZ used before the weights were pulled back onto the
/// reflectance grid: every column interpolated to the 1 nm CMF grid, then
/// X = k Σ S x̄ R with k = 100 / Σ S ȳ (CIE 15:2004 eqs 7.1-7.2).
std::vector<Vec3> XYZ_per_column(const SpectralData& refl, const SpectralData& illuminant, Observer observer) {
  const SpectralData& c = cmfs(observer);
  const auto S = interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], c.wavelengths, illuminant.linear);
  double sum = 0;
  for (size_t i = 0; i < S.size(); ++i) sum += S[i] * c.values[1][i];
  const double k = 100.0 / sum;
  std::vector<Vec3> out;
  for (const auto& col : refl.values) {
    const auto R = interpolate_spectrum(refl.wavelengths, col, c.wavelengths, refl.linear);
    Vec3 XYZ = Vec3::Zero();
    for (size_t i = 0; i < R.size(); ++i)
      for (int j = 0; j < 3; ++j) XYZ[j] += R[i] * S[i] * c.values[static_cast<size_t>(j)][i];
    out.push_back(k * XYZ);
  }
  return out;
}

/// `columns` reflectances in [0.02, 0.98] on `wavelengths`: smooth bumps plus a little noise, from
/// a fixed linear congruential sequence (the same in the native and wasm builds).
SpectralData planted_reflectances(const std::vector<double>& wavelengths, int columns, bool linear) {
  SpectralData d;
  d.wavelengths = wavelengths;
  d.linear = linear;
  unsigned long long state = 0x9E3779B97F4A7C15ull;
  auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  };
  for (int s = 0; s < columns; ++s) {
    const double centre = 380 + 350 * uniform(), width = 30 + 150 * uniform(), base = 0.05 + 0.4 * uniform();
    std::vector<double> v;
    for (double x : wavelengths) {
      const double bump = base + (0.9 - base) * std::exp(-0.5 * std::pow((x - centre) / width, 2));
      v.push_back(std::min(0.98, std::max(0.02, bump + 0.02 * (uniform() - 0.5))));
    }
    d.values.push_back(v);
    d.names.push_back(std::to_string(s + 1));
  }
  return d;
}

}  // namespace

// reflectances_to_XYZ pulls the illuminant x CMF weights back onto the reflectance grid
// (pull_back_weights) instead of interpolating every column to 1 nm: the same linear map, so the
// same XYZ up to summation order. Planted: 40 reflectances per grid, compared with the per-column
// formula; we see <= 4e-15 relative; tolerance 1e-12 relative to |XYZ| (all components >= 1 here).
TEST_CASE("reflectances_to_XYZ with pulled-back weights equals the per-column integration to 1e-12", "[spectra]") {
  struct Grid {
    const char* what;
    std::vector<double> wavelengths;
    bool linear;
  };
  std::vector<double> uneven = wavelength_grid(380, 730, 10);
  uneven.insert(uneven.begin() + 11, 485);  // between 480 and 490  // not uniform: linear
  const std::vector<Grid> grids = {
      {"Sprague 10 nm 380-730 (inside the CMF range)", wavelength_grid(380, 730, 10), false},
      {"Sprague 5 nm 300-900 (beyond both ends)", wavelength_grid(300, 900, 5), false},
      {"Sprague 5 nm 382.5-727.5 (off the integer grid)", wavelength_grid(382.5, 727.5, 5), false},
      {"Sprague 10 nm 401.3-691.3", wavelength_grid(401.3, 691.3, 10), false},
      {"Sprague 20 nm 420-680 (starts and ends inside)", wavelength_grid(420, 680, 20), false},
      {"Sprague 0.7 nm 400-700 (finer than the CMFs)", wavelength_grid(400, 699.6, 0.7), false},
      {"Sprague, 6 samples 400-700 at 60 nm", wavelength_grid(400, 700, 60), false},
      {"linear flag, 10 nm 380-730", wavelength_grid(380, 730, 10), true},
      {"linear flag, 5 nm 362.5-822.5", wavelength_grid(362.5, 822.5, 5), true},
      {"linear: not uniform", uneven, false},
      {"linear: 5 samples 400-720", wavelength_grid(400, 720, 80), false},
      {"one sample at 555 nm", {555.0}, false},
  };
  double worst = 0;
  for (const auto& g : grids)
    for (const char* ill : {"D65", "A", "F11", "D4500"})
      for (Observer obs : {Observer::CIE1931_2, Observer::CIE1964_10}) {
        const SpectralData refl = planted_reflectances(g.wavelengths, 40, g.linear);
        const SpectralData illuminant = illuminant_spd(ill);
        const auto got = reflectances_to_XYZ(refl, illuminant, obs);
        const auto want = XYZ_per_column(refl, illuminant, obs);
        REQUIRE(got.size() == want.size());
        for (size_t s = 0; s < got.size(); ++s)
          for (int k = 0; k < 3; ++k) {
            const double rel = std::abs(got[s][k] - want[s][k]) / std::abs(want[s][k]);
            if (rel > worst) {
              worst = rel;
              UNSCOPED_INFO("worst so far: " << g.what << ", " << ill << ", " << observer_name(obs) << ", column " << s
                                             << ", component " << k << ": pulled back " << got[s][k]
                                             << ", per column " << want[s][k]);
            }
          }
      }
  INFO("worst relative |pulled back - per column| = " << worst << " (tolerance 1e-12)");
  CHECK(worst < 1e-12);
}

TEST_CASE("reflectances_to_XYZ keeps interpolate_spectrum's errors and ignores samples it never reads", "[spectra]") {
  const SpectralData d65 = illuminant_spd("D65");
  SpectralData refl = planted_reflectances(wavelength_grid(300, 900, 5), 3, false);
  // 300 nm lies outside every Sprague window the 360-830 nm grid uses: a NaN there changes nothing.
  const auto before = reflectances_to_XYZ(refl, d65);
  refl.values[1][0] = std::nan("");
  const auto after = reflectances_to_XYZ(refl, d65);
  CHECK(after[1] == before[1]);
  // ... but a NaN at a sample that is read makes XYZ NaN, as before.
  refl.values[1][30] = std::nan("");
  CHECK(std::isnan(reflectances_to_XYZ(refl, d65)[1][1]));
  // No columns: no XYZ, whatever the grid.
  SpectralData none;
  CHECK(reflectances_to_XYZ(none, d65).empty());
  // A column of the wrong length, or a grid that is not increasing: the same codes as before.
  SpectralData bad = planted_reflectances(wavelength_grid(380, 730, 10), 3, false);
  bad.values[2].pop_back();
  tristim::test::require_code([&] { reflectances_to_XYZ(bad, d65); }, ErrorCode::InvalidArgument);
  bad = planted_reflectances(wavelength_grid(380, 730, 10), 3, false);
  std::swap(bad.wavelengths[3], bad.wavelengths[4]);
  tristim::test::require_code([&] { reflectances_to_XYZ(bad, d65); }, ErrorCode::NonMonotonic);
}

TEST_CASE("catalog: the observers' ids are the ones parse_observer reads and observer_name writes", "[spectra][catalog]") {
  const auto observers = list_observers();
  REQUIRE(observers.size() == 2);
  for (const ObserverInfo& o : observers) {
    INFO(o.id);
    CHECK(observer_name(parse_observer(o.id)) == o.id);
    CHECK(o.name.find(o.id) != std::string::npos);
  }
}

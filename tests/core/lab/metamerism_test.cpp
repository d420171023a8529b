// The metamerism explorer: a constructed metamer matches exactly under the first light (planted),
// its ΔE00 under the second recomputed by an independent path, a planted pair found by the search,
// and the pruned search the same as comparing every pair.
#include <algorithm>
#include <cmath>

#include "refused.hpp"
#include "test_support.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

const std::vector<double>& chip(const std::string& id) {
  const SpectralData& m = munsell_reflectances();
  return m.values[static_cast<size_t>(std::find(m.names.begin(), m.names.end(), id) - m.names.begin())];
}

// ΔE00 of two reflectances for the observer under `light`, through sd_to_XYZ (the CIE 15
// integration of each spectrum; the explorer uses a matrix built from unit spectra instead) and
// delta_E_CIE2000 (checked against Sharma et al.'s pairs, tests/data/colour-science).
double dE00_observer(const std::vector<double>& wl, const std::vector<double>& a, const std::vector<double>& b,
                     const std::string& light) {
  const SpectralData S = illuminant_spd(light);
  const Vec3 w = illuminant_white_XYZ(S);
  return delta_E_CIE2000(XYZ_to_Lab(sd_to_XYZ(wl, a, S), w), XYZ_to_Lab(sd_to_XYZ(wl, b, S), w));
}

SpectralData subset(const std::vector<std::string>& ids) {
  const SpectralData& m = munsell_reflectances();
  SpectralData s;
  s.wavelengths = m.wavelengths;
  for (const auto& id : ids) {
    s.names.push_back(id);
    s.values.push_back(chip(id));
  }
  return s;
}

}  // namespace

TEST_CASE("lab metamers: a constructed metamer matches the chip exactly under the first light, not under the second") {
  MetamerOptions o;  // D65, then A, CIE 1931
  const MetamerResult r = construct_metamer(o, "5R5/6");
  REQUIRE(r.pairs.size() == 1);
  const MetamerPair& p = r.pairs[0];
  const auto& wl = r.wavelengths;
  CHECK(p.reflectance_a == chip("5R5/6"));
  CHECK(p.alpha > 0);
  CHECK(*std::min_element(p.reflectance_b.begin(), p.reflectance_b.end()) >= 0);
  CHECK(*std::max_element(p.reflectance_b.begin(), p.reflectance_b.end()) <= 1);
  // the black touches a bound: α is the largest that keeps the metamer in [0, 1]
  const double lo = *std::min_element(p.reflectance_b.begin(), p.reflectance_b.end());
  const double hi = *std::max_element(p.reflectance_b.begin(), p.reflectance_b.end());
  CHECK((lo < 1e-12 || hi > 1 - 1e-12));
  const SpectralData d65 = illuminant_spd("D65");
  const Vec3 Xa = sd_to_XYZ(wl, p.reflectance_a, d65), Xb = sd_to_XYZ(wl, p.reflectance_b, d65);
  INFO("XYZ a " << Xa.transpose() << "  b " << Xb.transpose());
  CHECK((Xa - Xb).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(p.views[0].dE00_1 < 1e-9);
  const double dE2 = dE00_observer(wl, p.reflectance_a, p.reflectance_b, "A");
  CHECK(std::abs(p.views[0].dE00_2 - dE2) < 1e-9);
  CHECK(dE2 > 1.0);  // not a match under A
  CHECK((p.views[0].XYZ_a1 - Xa).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("lab metamers: a metamer for a camera matches its RGB under the first light, and the observer sees a difference") {
  MetamerOptions o;
  o.camera = "Canon_EOS_5D_Mark_II";
  o.match = "camera";
  o.second = "F11";
  const MetamerResult r = construct_metamer(o, "5PB4/10");
  const MetamerPair& p = r.pairs.at(0);
  REQUIRE(p.views.size() == 2);
  CHECK(p.views[1].viewer == "Canon_EOS_5D_Mark_II");
  SpectralData two;
  two.wavelengths = r.wavelengths;
  two.names = {"a", "b"};
  two.values = {p.reflectance_a, p.reflectance_b};
  const auto rgb = simulate_camera_RGB(camera_ssf(o.camera), two, illuminant_spd("D65"));
  INFO("RGB a " << rgb[0].transpose() << "  b " << rgb[1].transpose());
  CHECK((rgb[0] - rgb[1]).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(p.views[1].dE00_1 < 1e-9);
  CHECK(p.views[1].dE00_2 > 1.0);
  // the eye is not the camera: the pair the camera cannot tell apart differs for the observer
  CHECK(std::abs(p.views[0].dE00_1 - dE00_observer(r.wavelengths, p.reflectance_a, p.reflectance_b, "D65")) < 1e-9);
  CHECK(p.views[0].dE00_1 > 0.1);
}

TEST_CASE("lab metamers: the search finds a pair planted into a small set") {
  MetamerOptions o;
  const MetamerResult made = construct_metamer(o, "10GY5/6");
  SpectralData set = subset({"5R5/6", "10GY5/6", "5PB4/10", "2.5Y8/4", "5R5/8", "5RP6/6"});
  set.names.push_back("planted");
  set.values.push_back(made.pairs[0].reflectance_b);
  const MetamerResult r = metamer_pairs_in(o, set);
  REQUIRE(r.pairs.size() >= 1);
  CHECK(r.matching == 1);
  CHECK(r.pairs[0].a == "10GY5/6");
  CHECK(r.pairs[0].b == "planted");
  CHECK(r.pairs[0].views[0].dE00_1 < 1e-9);
  CHECK(std::abs(r.pairs[0].views[0].dE00_2 - dE00_observer(set.wavelengths, chip("10GY5/6"), set.values.back(), "A")) < 1e-9);
  CHECK(r.all_pairs == 21);
  CHECK(r.compared < r.all_pairs);  // the L* window skipped some
}

TEST_CASE("lab metamers: the L-star window search finds exactly the pairs a full comparison finds") {
  const SpectralData& m = munsell_reflectances();
  SpectralData set;
  set.wavelengths = m.wavelengths;
  for (size_t i = 0; i < m.size(); i += 3) {  // 423 chips: 89 253 pairs
    set.names.push_back(m.names[i]);
    set.values.push_back(m.values[i]);
  }
  MetamerOptions o;
  o.max_match = 3;
  o.top = 1000000;
  const MetamerResult r = metamer_pairs_in(o, set);
  const SpectralData S = illuminant_spd("D65");
  const Vec3 w = illuminant_white_XYZ(S);
  const auto X = reflectances_to_XYZ(set, S);
  int brute = 0;
  for (size_t i = 0; i < X.size(); ++i)
    for (size_t j = i + 1; j < X.size(); ++j)
      if (delta_E_CIE2000(XYZ_to_Lab(X[i], w), XYZ_to_Lab(X[j], w)) < o.max_match) ++brute;
  INFO("window " << r.matching << " of " << r.compared << " compared; brute force " << brute);
  CHECK(brute > 10);
  CHECK(r.matching == brute);
  CHECK(static_cast<int>(r.pairs.size()) == brute);
  CHECK(r.compared < r.all_pairs / 5);
  for (size_t k = 1; k < r.pairs.size(); ++k) CHECK(r.pairs[k - 1].views[0].dE00_2 >= r.pairs[k].views[0].dE00_2);
}

TEST_CASE("lab metamers: bad options are refused with a code") {
  const auto refused = [](ErrorCode code, auto set) {
    test::require_refused<MetamerOptions>(code, set, [](const MetamerOptions& o) { return metamer_pairs(o); });
  };
  refused(ErrorCode::InvalidArgument, [](auto& o) { o.match = "camera"; });  // no camera
  refused(ErrorCode::UnknownId, [](auto& o) { o.match = "eye"; });
  refused(ErrorCode::InvalidArgument, [](auto& o) { o.max_match = 0; });
  refused(ErrorCode::UnknownId, [](auto& o) { o.second = "Z99"; });
  refused(ErrorCode::UnknownId, [](auto& o) { o.camera = "no such camera"; });
  test::require_code([] { construct_metamer(MetamerOptions{}, "99Q5/6"); }, ErrorCode::UnknownId);
}

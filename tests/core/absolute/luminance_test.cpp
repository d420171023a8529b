// Guarnera 2018 section 3.1 on the virtual bracket camera: eq (8) fit, the linearisation row,
// saturation measured from the data, the luminance training with exposure scaling and the
// reciprocity report.
#include <cmath>

#include "absolute_bench.hpp"
#include "test_support.hpp"
#include "tristim/absolute/luminance.hpp"
#include "tristim/linearisation/guarnera2018.hpp"

using namespace tristim;

TEST_CASE("absolute: eq (8) fit recovers a planted power law across exposures", "[absolute]") {
  const InverseOecf truth{0.002, 3.7, 1.06};
  std::vector<OecfSample> s;
  for (double eps : {0.5, 1.0, 2.0, 4.0})
    for (double Y = 5; Y <= 200; Y += 15) s.push_back({truth.forward(Y * eps), eps, Y});
  const OecfFit f = fit_inverse_oecf_Guarnera2018(s);
  INFO("k1 " << f.curve.k1 << " k2 " << f.curve.k2 << " k3 " << f.curve.k3 << " rms " << f.rms_relative);
  CHECK(f.curve.k3 == Approx(truth.k3).epsilon(1e-6));
  CHECK(f.curve.k2 == Approx(truth.k2).epsilon(1e-6));
  CHECK(f.curve.k1 == Approx(truth.k1).margin(1e-7));
  CHECK(f.rms_relative < 1e-7);
  // eq (8) is the inverse of the OECF.
  for (double h : {0.01, 1.0, 50.0}) CHECK(f.curve(f.curve.forward(h)) == Approx(h).epsilon(1e-12));
}

TEST_CASE("absolute: eq (8) fit refuses degenerate data with codes", "[absolute]") {
  test::require_code([] { fit_inverse_oecf_Guarnera2018({{0.1, 1, 10}, {0.2, 1, 20}}); }, ErrorCode::TooFewPatches);
  test::require_code([] { fit_inverse_oecf_Guarnera2018({{0.1, 1, 10}, {0.1, 1, 20}, {0.1, 1, 30}}); }, ErrorCode::IllPosed);
  test::require_code([] { fit_inverse_oecf_Guarnera2018({{0.1, 1, -1}, {0.2, 1, 20}, {0.3, 1, 30}}); }, ErrorCode::NegativeValue);
  test::require_code([] { fit_inverse_oecf_Guarnera2018({{0.3, 1, 10}, {0.2, 1, 20}, {0.1, 1, 30}}); }, ErrorCode::NonMonotonic);
}

TEST_CASE("absolute: the Guarnera2018 row of the linearisation table", "[absolute][linearisation]") {
  const auto& row = linearisation_method("Guarnera2018");
  CHECK(row.info.reference.find("eqs (7)-(8)") != std::string::npos);
  // A planted camera: DN = n + (S − n)·(A_c/A_G)·(k2·Y·ε)^k3, at t = 1/60 s, f/8.
  const double n = 6, S = 15000, eps = (1.0 / 60) / 64, area[3] = {0.5, 1.0, 0.7}, k3[3] = {1.02, 1.0, 0.98};
  LinearisationData d;
  d.camera_RGB.resize(31, 3);
  d.reference_XYZ.resize(31, 3);
  for (int i = 0; i < 31; ++i) {
    const double Y = 30.0 * i;
    d.reference_XYZ.row(i) << Y, Y, Y;
    for (int c = 0; c < 3; ++c)
      d.camera_RGB(i, c) = std::min(S, n + (S - n) * area[c] * std::pow(Y * eps / 0.25, k3[c]));
  }
  MethodChoice choice{"Guarnera2018", {{"noise_floor", n}, {"saturation", S}, {"area_R", 0.5}, {"area_B", 0.7},
                                       {"exposure_s", 1.0 / 60}, {"f_number", 8}}, {}};
  const Linearisation l = fit_linearisation(choice, d);
  const PatchMatrix L = linearise(l, d.camera_RGB);
  double worst = 0;
  for (int i = 1; i < 31; ++i)
    for (int c = 0; c < 3; ++c)
      if (d.camera_RGB(i, c) < S) worst = std::max(worst, std::fabs(L(i, c) / d.reference_XYZ(i, 1) - 1));
  INFO("worst relative error " << worst);
  CHECK(worst < 1e-6);
  CHECK(l.coefficients[0][2] == Approx(1.02).epsilon(1e-5));
  // The row's inverse gives the stored values back (eq 8's OECF, then eq 7 undone).
  const PatchMatrix back = delinearise(l, L);
  for (int i = 1; i < 31; ++i)
    for (int c = 0; c < 3; ++c)
      if (d.camera_RGB(i, c) < S) CHECK(back(i, c) == Approx(d.camera_RGB(i, c)).epsilon(1e-9));
  // Missing luminances are refused.
  LinearisationData no_Y = d;
  no_Y.reference_XYZ.resize(0, 3);
  test::require_code([&] { fit_linearisation(choice, no_Y); }, ErrorCode::PatchMismatch);
}

TEST_CASE("absolute: saturation measured below LibRaw's optimistic maximum", "[absolute]") {
  const auto& b = test::bench();
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << " level " << b.saturation.level[c] << " reported " << b.saturation.reported[c]);
    CHECK(b.saturation.measured[c]);
    CHECK(b.saturation.level[c] == Approx(b.sensor.saturation).margin(1.0));
    CHECK(b.saturation.fraction[c] == Approx(15000.0 / 16000).epsilon(1e-4));
    CHECK(b.saturation.clipped_pixels[c] > 0);
  }
  // Unclipped frames keep LibRaw's level (nothing to measure).
  const RawImage dim = capture_virtual(b.sensor, uniform_scene(40, 30, equal_energy_spectrum(), 100), b.bracket[0], 5);
  const SaturationEstimate s = measure_saturation({&dim});
  CHECK_FALSE(s.measured[1]);
  CHECK(s.level[1] == 16000);
}

TEST_CASE("absolute: exposure settings come from the RAW metadata", "[absolute]") {
  RawMetadata m;
  m.shutter_s = 1.0 / 125;
  m.f_number = 5.6;
  m.iso = 200;
  const ExposureSettings e = exposure_from_metadata(m, "a.CR2");
  CHECK(e.factor(100) == Approx(2.0 / 125 / (5.6 * 5.6)));
  CHECK(e.label() == "1/125 s f/5.6 ISO 200");
  m.f_number = 0;
  test::require_code([&] { exposure_from_metadata(m, "a.CR2"); }, ErrorCode::MissingMetadata);
}

TEST_CASE("absolute: luminance training on the virtual bracket (0-890 cd/m², 5 exposures)", "[absolute]") {
  const auto& b = test::bench();
  const LuminanceFit& L = b.profile.luminance;
  for (int c = 0; c < 3; ++c)
    INFO("RGB"[c] << ": k1 " << L.curves[c].k1 << " k2 " << L.curves[c].k2 << " k3 " << L.curves[c].k3 << " rms "
                  << L.fits[c].rms_relative << " samples " << L.fits[c].samples);
  CHECK(L.reciprocity_ok);
  INFO(L.message);
  CHECK(L.exposures.size() == 5);
  // The true exponents of the virtual OECF (normalised u^k3) are recovered.
  CHECK(L.curves[0].k3 == Approx(1.03).epsilon(0.01));
  CHECK(L.curves[1].k3 == Approx(1.00).epsilon(0.01));
  CHECK(L.curves[2].k3 == Approx(0.97).epsilon(0.01));
  // Every unsaturated training stimulus: eq (10) gives Y within the paper's 2.4 % (Y ≥ 30).
  double worst = 0;
  for (const auto& s : b.stimuli) {
    if (!s.luminance_set || s.XYZ[1] < 30) continue;
    const Vec3 l = stimulus_luminance(s, b.normalisation, L);
    for (int c = 0; c < 3; ++c)
      if (!s.saturated[c] && stimulus_normalised(s, b.normalisation, c) > 0.05)
        worst = std::max(worst, std::fabs(l[c] / s.XYZ[1] - 1));
  }
  INFO("worst relative error of L over the training set (R' > 0.05): " << worst);
  CHECK(worst < 0.024);
}

TEST_CASE("absolute: a reciprocity failure is reported, not hidden", "[absolute]") {
  test::BenchConfig c;
  c.reciprocity_exponent = 0.9;  // effective exposure ∝ t^0.9
  const auto& b = test::bench(c);
  const LuminanceFit& L = b.profile.luminance;
  INFO(L.message);
  CHECK_FALSE(L.reciprocity_ok);
  CHECK(L.message.find("reciprocity fails") != std::string::npos);
  // The shortest exposure (1/250 s) sees 1.15x its nominal share relative to the middle one.
  double lo = 1e9, hi = 0;
  for (const auto& e : L.exposures) {
    lo = std::min(lo, e.scale_ratio[1]);
    hi = std::max(hi, e.scale_ratio[1]);
  }
  CHECK(hi / lo > 1.2);
}

TEST_CASE("absolute: non-monotonic training stimuli are refused with NonMonotonic", "[absolute]") {
  const auto& b = test::bench();
  std::vector<TrainingStimulus> s = b.stimuli;
  // Swap the measured luminances of two stimuli of the same exposure.
  int i = -1, j = -1;
  for (size_t k = 0; k < s.size(); ++k) {
    if (!s[k].luminance_set || s[k].exposure.exposure_s != b.bracket[2].exposure_s) continue;
    if (s[k].XYZ[1] == 150) i = static_cast<int>(k);
    if (s[k].XYZ[1] == 450) j = static_cast<int>(k);
  }
  REQUIRE(i >= 0);
  REQUIRE(j >= 0);
  std::swap(s[i].XYZ, s[j].XYZ);
  test::require_code([&] { fit_luminance_Guarnera2018(s, b.normalisation); }, ErrorCode::NonMonotonic);
  // All saturated: nothing to fit.
  std::vector<TrainingStimulus> sat = b.stimuli;
  for (auto& x : sat) x.saturated = {true, true, true};
  test::require_code([&] { fit_luminance_Guarnera2018(sat, b.normalisation); }, ErrorCode::NoUsableData);
}

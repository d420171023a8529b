// Spectral sensitivities estimated from one simulated ColorChecker photo under D65 (Jiang, Liu,
// Gu & Süsstrunk 2013: PCA basis of the built-in cameras + smoothness-constrained solve),
// leave-one-camera-out over the 52 built-in cameras; CSV output; coded errors.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "test_support.hpp"
#include "tristim/absolute/fields.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/sensitivities.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

TEST_CASE("absolute: sensitivities estimated leave-one-camera-out over the 52 cameras", "[absolute][sensitivities]") {
  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData d65 = illuminant_spd("D65");
  for (double noise : {0.0, 0.002}) {
    std::vector<double> rms, err_R, err_B;
    std::string worst_camera;
    double worst = 0;
    for (const auto& cam : camera_names()) {
      const SpectralData truth = camera_ssf(cam);
      SimulationOptions so;  // linear camera RGB, white patch G ≈ 0.9
      so.noise_sigma = noise;
      so.seed = 11;
      const auto rgb = simulate_camera_RGB(truth, refl, d65, so);
      SensitivityOptions o;
      o.exclude_cameras = {cam};  // the held-out camera is not in the basis
      const SensitivityEstimate e = estimate_sensitivities_Jiang2013(rgb, refl, d65, o);
      CHECK(e.basis_cameras == 51);
      rms.push_back(sensitivity_rms(e.ssf, truth));
      const auto A = channel_areas(truth);
      const double r = std::fabs((e.areas[0] / e.areas[1]) / (A[0] / A[1]) - 1);
      const double b = std::fabs((e.areas[2] / e.areas[1]) / (A[2] / A[1]) - 1);
      err_R.push_back(r);
      err_B.push_back(b);
      if (std::max(r, b) > worst) {
        worst = std::max(r, b);
        worst_camera = cam;
      }
      INFO(cam << " noise " << noise << ": A_R/A_G off by " << r << ", A_B/A_G by " << b << ", residual " << e.residual_rms);
      CHECK(r < 0.02);
      CHECK(b < 0.02);
    }
    const Summary s = summarize(rms), R = summarize(err_R), B = summarize(err_B);
    std::printf("Sensitivities, leave-one-camera-out (52 cameras, ColorChecker under D65, noise %.3g, K = 4):\n"
                "  RMS (each channel peak 1): median %.4f, p95 %.4f, max %.4f\n"
                "  |A_R/A_G error| median %.4f max %.4f; |A_B/A_G error| median %.4f max %.4f (worst: %s)\n",
                noise, s.median, s.p95, s.max, R.median, R.max, B.median, B.max, worst_camera.c_str());
    CHECK(s.median < (noise > 0 ? 0.04 : 0.025));
  }
}

TEST_CASE("absolute: a camera in the basis is recovered almost exactly — CSV keeps channel ratios", "[absolute][sensitivities]") {
  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData d65 = illuminant_spd("D65");
  const SpectralData truth = camera_ssf("Nikon_D850");
  const SensitivityEstimate e = estimate_sensitivities_Jiang2013(simulate_camera_RGB(truth, refl, d65), refl, d65);
  CHECK(e.residual_rms < 0.01);
  const std::string csv = sensitivities_to_csv(e.ssf);
  CHECK(csv.rfind("wavelength_nm,R,G,B\n380,", 0) == 0);
  const SpectralData back = read_ssf_csv(csv, "estimate.csv");
  double peak = 0;
  for (const auto& v : back.values) peak = std::max(peak, *std::max_element(v.begin(), v.end()));
  CHECK(peak == Approx(1.0));
  const auto a = channel_areas(back), b = channel_areas(e.ssf);
  CHECK(a[0] / a[1] == Approx(b[0] / b[1]).epsilon(1e-6));
}

TEST_CASE("absolute: sensitivity estimation refuses bad input with codes", "[absolute][sensitivities]") {
  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData d65 = illuminant_spd("D65");
  const auto rgb = simulate_camera_RGB(camera_ssf("Nikon_D850"), refl, d65);
  test::require_code([&] { estimate_sensitivities_Jiang2013({rgb.begin(), rgb.begin() + 10}, refl, d65); }, ErrorCode::PatchMismatch);
  SpectralData three = refl;
  three.values.resize(3);
  three.names.resize(3);
  test::require_code([&] { estimate_sensitivities_Jiang2013({rgb.begin(), rgb.begin() + 3}, three, d65); }, ErrorCode::TooFewPatches);
  SensitivityOptions o;
  o.exclude_cameras = {"Leica M3"};
  test::require_code([&] { estimate_sensitivities_Jiang2013(rgb, refl, d65, o); }, ErrorCode::UnknownId);
  std::vector<Vec3> dark(rgb.size(), Vec3(0.1, 0, 0.1));
  test::require_code([&] { estimate_sensitivities_Jiang2013(dark, refl, d65); }, ErrorCode::InvalidArgument);
}

TEST_CASE("absolute: sensitivities paired by patch id (rows in any order, extra rows left out)", "[absolute][sensitivities]") {
  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData d65 = illuminant_spd("D65");
  const auto rgb = simulate_camera_RGB(camera_ssf("Nikon_D850"), refl, d65);
  const SensitivityEstimate direct = estimate_sensitivities_Jiang2013(rgb, refl, d65);
  // Reversed rows, ids written with a leading zero ("A01"), plus one id no reflectance has.
  std::vector<std::string> ids;
  std::vector<Vec3> rows;
  for (size_t i = refl.names.size(); i-- > 0;) {
    std::string id = refl.names[i];
    if (id.size() == 2) id = id.substr(0, 1) + "0" + id.substr(1);
    ids.push_back(id);
    rows.push_back(rgb[i]);
  }
  ids.push_back("Z99");
  rows.push_back(Vec3(1, 1, 1));
  const SensitivityEstimate e = estimate_sensitivities_by_id(ids, rows, refl, d65);
  CHECK(e.patches == static_cast<int>(refl.names.size()));
  CHECK(e.unpaired == 1);
  REQUIRE(e.ids.size() == refl.names.size());
  CHECK(e.ids.front() == ids.front());
  CHECK(sensitivity_rms(e.ssf, direct.ssf) < 1e-9);
  test::require_code([&] { estimate_sensitivities_by_id({"A1"}, rows, refl, d65); }, ErrorCode::PatchMismatch);
  test::require_code([&] { estimate_sensitivities_by_id({"Z98", "Z99"}, {rows[0], rows[1]}, refl, d65); }, ErrorCode::PatchMismatch);
}

TEST_CASE("absolute: the sensitivity estimate states its areas' uncertainty — a held-out camera lies within it", "[absolute][sensitivities]") {
  // Canon EOS 5D Mark II held out of the basis (as a camera unlike the 52 would be), noise-free
  // ColorChecker under D65: the true A_R/A_G and A_B/A_G lie within the stated ±u (coverage 3),
  // u is not vanishingly small, and nothing warns.
  const SpectralData refl = chart_reflectances("cc24"), d65 = illuminant_spd("D65");
  const std::string cam = "Canon_EOS_5D_Mark_II";
  const SpectralData truth = camera_ssf(cam);
  const auto rgb = simulate_camera_RGB(truth, refl, d65);
  SensitivityOptions o;
  o.exclude_cameras = {cam};
  const SensitivityEstimate e = estimate_sensitivities_Jiang2013(rgb, refl, d65, o);
  const SensitivityUncertainty u = sensitivity_uncertainty(rgb, refl, d65, o, e);
  const auto A = channel_areas(truth);
  const double err[2] = {u.ratio[0] / (A[0] / A[1]) - 1, u.ratio[1] / (A[2] / A[1]) - 1};
  CHECK(u.loo_bases == 51);
  CHECK(u.components_tried == std::vector<int>{3, 4, 5});
  for (int r = 0; r < 2; ++r) {
    INFO("ratio " << r << ": error " << err[r] << ", stated ±" << u.u[r] << " (LOO " << u.u_loo[r] << ", K " << u.u_K[r] << ")");
    CHECK(std::fabs(err[r]) <= u.u[r]);
    CHECK(u.u[r] > 0.0005);
    CHECK(u.u[r] == Approx(3 * std::hypot(u.u_loo[r], u.u_K[r])));
  }
  CHECK(u.warnings.empty());
  CHECK(u.message.empty());
  CHECK(u.nearest_distance < u.distance_limit);
}

TEST_CASE("absolute: a camera without an IR-cut filter is flagged as outside the basis", "[absolute][sensitivities]") {
  // A synthetic sensor without an IR-cut filter: a built-in camera's curves with the silicon's
  // near-infrared response added beyond 650 nm in every channel (rising to 0.6 of the peak at
  // 780 nm). The 52 cameras all cut the infrared, so the basis cannot follow it.
  const SpectralData refl = chart_reflectances("cc24"), d65 = illuminant_spd("D65");
  SpectralData ssf = camera_ssf("Canon_EOS_5D_Mark_II");
  double peak = 0;
  for (const auto& v : ssf.values) peak = std::max(peak, *std::max_element(v.begin(), v.end()));
  for (auto& v : ssf.values)
    for (size_t i = 0; i < ssf.wavelengths.size(); ++i)
      if (ssf.wavelengths[i] > 650) v[i] += 0.6 * peak * (ssf.wavelengths[i] - 650) / 130;
  const auto rgb = simulate_camera_RGB(ssf, refl, d65);
  const SensitivityEstimate e = estimate_sensitivities_Jiang2013(rgb, refl, d65);
  const SensitivityUncertainty u = sensitivity_uncertainty(rgb, refl, d65, {}, e);
  INFO("residual " << e.residual_rms << ", nearest " << u.nearest_camera << " at " << u.nearest_distance << ": " << u.message);
  CHECK(!u.warnings.empty());
  CHECK(u.message.find("unlike the") != std::string::npos);
}

TEST_CASE("absolute: the uncertainty's field list — JSON round trip exact, unknown members refused", "[absolute][sensitivities]") {
  // One list gives the CLI's "uncertainty" and the object the page gets; its reader takes back what
  // its writer wrote, member for member, and refuses what the list does not name.
  SensitivityUncertainty u;
  u.ratio = {0.4572284455105721, 0.7008403574692194};
  u.u_loo = {6.86e-4, 1.2067685403866057e-3};
  u.u_K = {1.9e-4, 5.57e-4};
  u.u = {2.1370647929991804e-3, 3.987e-3};
  u.coverage = 2;
  u.loo_bases = 51;
  u.components_tried = {3, 4, 5};
  u.nearest_camera = "Canon_EOS_M";
  u.nearest_distance = 0.035214111406810064;
  u.residual_limit = 0.02;
  u.distance_limit = 0.1;
  u.warnings = {"residual", "distance"};
  u.message = "two lines";
  const fields::Context ctx{ErrorCode::InvalidArgument, "uncertainty: "};
  const std::string text = fields::write(u).dump();
  SensitivityUncertainty back;
  fields::read(json::parse(text), back, ctx);
  CHECK(back.ratio == u.ratio);
  CHECK(back.u_loo == u.u_loo);
  CHECK(back.u_K == u.u_K);
  CHECK(back.u == u.u);
  CHECK(back.coverage == 2);
  CHECK(back.loo_bases == 51);
  CHECK(back.components_tried == u.components_tried);
  CHECK(back.nearest_camera == u.nearest_camera);
  CHECK(back.nearest_distance == u.nearest_distance);
  CHECK(back.residual_limit == u.residual_limit);
  CHECK(back.distance_limit == u.distance_limit);
  CHECK(back.warnings == u.warnings);
  CHECK(back.message == u.message);
  CHECK(fields::write(back).dump() == text);
  json::Value extra = json::parse(text);
  extra.set("area_ratio_R_G", 0.002);  // a name the list does not have
  test::require_code([&] { fields::read(extra, back, ctx); }, ErrorCode::InvalidArgument);
  json::Value short_u = json::parse(text);
  short_u.set("u", json::Value(std::vector<double>{0.002}));  // two ratios, two uncertainties
  test::require_code([&] { fields::read(short_u, back, ctx); }, ErrorCode::InvalidArgument);
}

TEST_CASE("absolute: the estimate's field list — JSON round trip exact, unknown members refused", "[absolute][sensitivities]") {
  // One list gives `tristim sensitivities estimate`'s JSON and the object the page gets; a real
  // estimate (a held-out camera, one patch id without a reflectance) written, read back, equal.
  const SpectralData refl = chart_reflectances("cc24"), d65 = illuminant_spd("D65");
  const std::vector<Vec3> rgb = simulate_camera_RGB(camera_ssf("Nikon_D5100"), refl, d65);
  std::vector<std::string> ids = refl.names;
  ids.back() = "Z99";
  SensitivityOptions o;
  o.exclude_cameras = {"Nikon_D5100"};
  const SensitivityEstimate e = estimate_sensitivities_by_id(ids, rgb, refl, d65, o);
  REQUIRE(e.unpaired == 1);
  const fields::Context ctx{ErrorCode::InvalidArgument, "estimate: "};
  const json::Value written = fields::write(e);
  CHECK(written.find("method")->as_string() == "Jiang2013");
  CHECK(written.find("area_ratio_R_G")->as_number() == e.areas[0] / e.areas[1]);
  CHECK(written.find("area_ratio_B_G")->as_number() == e.areas[2] / e.areas[1]);
  const std::string text = written.dump();
  SensitivityEstimate back;
  fields::read(json::parse(text), back, ctx);
  CHECK((back.patches == 23 && back.basis_cameras == 51));
  CHECK(std::tie(back.unpaired, back.components, back.clipped, back.residual_rms, back.areas, back.ids) ==
        std::tie(e.unpaired, e.components, e.clipped, e.residual_rms, e.areas, e.ids));
  CHECK(back.residual == e.residual);
  CHECK(std::tie(back.ssf.wavelengths, back.ssf.names, back.ssf.values) == std::tie(e.ssf.wavelengths, e.ssf.names, e.ssf.values));
  CHECK(fields::write(back).dump() == text);
  const auto refused = [&](const char* name, json::Value v) {
    json::Value x = json::parse(text);
    x.set(name, std::move(v));
    test::require_code([&] { fields::read(x, back, ctx); }, ErrorCode::InvalidArgument);
  };
  refused("unpaired_rgb_rows", 0);                     // a name the list does not have
  refused("method", "Jiang2014");                      // the one method it states
  refused("area_ratio_R_G", "0.45");                   // a ratio that is not a number
  refused("residual", json::Value(std::vector<double>{0.1, 0.2}));  // three channels
  json::Value short_ssf = json::parse(text);
  json::Value curves = *short_ssf.find("ssf");
  curves.set("names", json::Value::array());           // three columns, no names
  short_ssf.set("ssf", curves);
  test::require_code([&] { fields::read(short_ssf, back, ctx); }, ErrorCode::InvalidArgument);
  // The uncertainty from the same inputs, paired alike, equals the one from the pairs themselves.
  SpectralData paired = refl;
  paired.names.pop_back();
  paired.values.pop_back();
  const std::vector<Vec3> paired_rgb(rgb.begin(), rgb.end() - 1);
  const SensitivityUncertainty by_id = sensitivity_uncertainty_by_id(ids, rgb, refl, d65, o, e);
  const SensitivityUncertainty direct = sensitivity_uncertainty(paired_rgb, paired, d65, o, e);
  CHECK(by_id.u == direct.u);
  CHECK(by_id.loo_bases == 51);
}

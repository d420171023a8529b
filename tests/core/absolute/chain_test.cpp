// The whole absolute chain (Guarnera 2018 eq 4) on the virtual bracket camera, evaluated as
// section 4.1 does: ΔE94, ΔE00 (white per eq 16, or E at the largest luminance), NRMSE per X, Y,
// Z, relative Y error, median absolute error in cd/m². Figures are printed (Table 3/4 layout).
//
// Three settings:
//  1. equal-tristimulus test stimuli between the training ones (the luminance module, eq 9);
//  2. a ColorChecker under D65, A and F2 with the colour module trained on other reflective
//     colours (the ColorChecker SG patches unlike any of the 24) under the scene's illuminant,
//     T2R (eq 15, the paper's best for its booth scenes) — the brief's thresholds hold here;
//  3. the same chart with the paper's own colour training (24 projected ColorChecker colours,
//     T1): D65 meets the thresholds, A and F2 do not — a three-primary projector spans only
//     three spectral shapes, so its matrix does not transfer to broadband or line spectra for
//     this camera (printed, and bounded so a regression shows; see notes/absolute.md).
#include <cmath>
#include <cstdio>

#include "absolute_bench.hpp"
#include "test_support.hpp"
#include "tristim/absolute/profile.hpp"

using namespace tristim;

namespace {

void print(const char* what, const AbsoluteMetrics& m) {
  std::printf("  %-26s dE94 median %.3f mean %.3f max %.3f | dE00 median %.3f mean %.3f max %.3f | NRMSE X %.4f "
              "Y %.4f Z %.4f | rel Y %.4f | median |dY| %.2f cd/m2\n",
              what, m.metrics.dE94.median, m.metrics.dE94.mean, m.metrics.dE94.max, m.metrics.dE00.median,
              m.metrics.dE00.mean, m.metrics.dE00.max, m.metrics.NRMSE[0], m.metrics.NRMSE[1], m.metrics.NRMSE[2],
              m.relative_Y_error, m.median_absolute_error[1]);
}

double mean_nrmse(const AbsoluteMetrics& m) { return m.metrics.NRMSE.mean(); }

/// A scene photographed at every exposure of the bench's bracket.
struct Shots {
  std::vector<RawImage> frames;
  std::vector<const RawImage*> all() const {
    std::vector<const RawImage*> v;
    for (const auto& f : frames) v.push_back(&f);
    return v;
  }
};
Shots shoot(const test::AbsoluteBench& b, const VirtualScene& scene, std::uint64_t seed) {
  Shots s;
  for (size_t e = 0; e < b.bracket.size(); ++e) s.frames.push_back(capture_virtual(b.sensor, scene, b.bracket[e], seed + e));
  return s;
}

/// Per-pixel metrics of a profile on a grid scene: every single exposure, the fused bracket and
/// Algorithm 1.
struct Run {
  std::vector<AbsoluteMetrics> each;
  AbsoluteMetrics single, fused, recursive;
  double best_single = 1e9;  // lowest mean NRMSE of an exposure that saw every pixel
};
Run run(const AbsoluteProfile& profile, const test::GridScene& g, const Shots& shots, const Vec3& white,
        bool per_pixel, int single_index = 2) {
  auto metrics = [&](const std::vector<float>& XYZ) {
    PatchMatrix est, truth;
    if (per_pixel) test::pixel_rows(XYZ, g, est, truth);
    else {
      est = test::patch_means(XYZ, g);
      truth = test::to_patch_matrix(g.XYZ);
    }
    return evaluate_absolute(est, truth, white);
  };
  Run r;
  for (const auto& f : shots.frames) {
    r.each.push_back(metrics(apply_absolute(profile, {&f}).XYZ));
    if (r.each.back().metrics.NRMSE.allFinite()) r.best_single = std::min(r.best_single, mean_nrmse(r.each.back()));
  }
  r.single = r.each[single_index];
  r.fused = metrics(apply_absolute(profile, shots.all()).XYZ);
  AbsoluteProfile rec = profile;
  rec.fusion = FusionMode::Recursive;
  r.recursive = metrics(apply_absolute(rec, shots.all()).XYZ);
  return r;
}

void print_run(const Run& r) {
  print("single shot (1/60 s f/8)", r.single);
  print("fused (5 exposures)", r.fused);
  print("Algorithm 1 (5 exposures)", r.recursive);
}

/// The colour module trained on the ColorChecker SG patches unlike every ColorChecker Classic
/// patch (spectral RMS difference > 0.03), under `illuminant`, photographed at 1/60 s f/8.
Model colour_from_sg(const test::AbsoluteBench& b, const std::string& illuminant, const std::string& transform) {
  const SpectralData sg = chart_reflectances("sg140"), cc = align_spectra(chart_reflectances("cc24"), sg.wavelengths);
  SpectralData keep;
  keep.wavelengths = sg.wavelengths;
  for (size_t k = 0; k < sg.size(); ++k) {
    double nearest = 1e9;
    for (const auto& c : cc.values) {
      double ss = 0;
      for (size_t i = 0; i < c.size(); ++i) ss += (c[i] - sg.values[k][i]) * (c[i] - sg.values[k][i]);
      nearest = std::min(nearest, std::sqrt(ss / c.size()));
    }
    if (nearest > 0.03) {
      keep.names.push_back(sg.names[k]);
      keep.values.push_back(sg.values[k]);
    }
  }
  const SpectralData spectra = reflected_spectra(keep, illuminant_spd(illuminant));
  double y_max = 0;
  for (size_t k = 0; k < spectra.size(); ++k) y_max = std::max(y_max, test::luminance_sum(spectra, static_cast<int>(k)));
  std::vector<double> Y;
  for (size_t k = 0; k < spectra.size(); ++k) Y.push_back(600 * test::luminance_sum(spectra, static_cast<int>(k)) / y_max);
  const test::GridScene g = test::grid_scene(b.sensor, spectra, Y, 14, 16);
  const AbsoluteProfile p = test::profile_for(b, g.scene.width, g.scene.height);
  const RawImage f = capture_virtual(b.sensor, g.scene, b.bracket[2], 800);
  const PatchMatrix L = test::patch_means(apply_absolute(p, {&f}).luminance.L, g);
  FitOptions fo;
  fo.objective = Objective::PatternSearch;  // eqs (11)-(12)
  std::printf("  colour module: %d SG patches unlike the ColorChecker's, under %s, %s\n", static_cast<int>(keep.size()),
              illuminant.c_str(), transform.c_str());
  return fit_Guarnera2018(L, test::to_patch_matrix(g.XYZ), transform, fo).model;
}

}  // namespace

TEST_CASE("absolute: equal-tristimulus test stimuli between the training ones (eq 9)", "[absolute]") {
  const auto& b = test::bench();
  SpectralData spectra;
  std::vector<double> Y;
  for (int v = 15; v <= 885; v += 30) {
    const SpectralData e = projector_spectra({Vec3(1, 1, 1)}, {"Y" + std::to_string(v)});
    spectra.wavelengths = e.wavelengths;
    spectra.names.push_back(e.names[0]);
    spectra.values.push_back(e.values[0]);
    Y.push_back(v);
  }
  const test::GridScene g = test::grid_scene(b.sensor, spectra, Y, 6, 24);
  const AbsoluteProfile p = test::profile_for(b, g.scene.width, g.scene.height);
  const Shots shots = shoot(b, g.scene, 200);
  const Vec3 white = white_equal_energy(890);  // Experiments (a), (c)
  std::printf("Equal-tristimulus test stimuli 15-885 cd/m2 (virtual %s), white E at 890 cd/m2:\n",
              test::BenchConfig().camera.c_str());
  for (bool per_pixel : {false, true}) {
    const Run r = run(p, g, shots, white, per_pixel);
    std::printf(" %s\n", per_pixel ? "per pixel" : "patch means");
    print_run(r);
    INFO((per_pixel ? "per pixel" : "patch means"));
    CHECK(r.single.relative_Y_error < 0.024);
    CHECK(r.fused.relative_Y_error < 0.024);
    CHECK(mean_nrmse(r.single) < 0.016);
    CHECK(mean_nrmse(r.fused) < 0.013);
    CHECK(mean_nrmse(r.fused) <= r.best_single * 1.02);
  }
}

TEST_CASE("absolute: ColorChecker under D65, A, F2 per pixel, colour module trained on other colours (T2R)", "[absolute]") {
  test::BenchConfig cfg;
  cfg.transform = "T2R";
  const auto& b = test::bench(cfg);
  std::printf("ColorChecker per pixel (virtual %s), white per eq (16):\n", cfg.camera.c_str());
  for (const char* ill : {"D65", "A", "F2"}) {
    const test::GridScene c = test::chart_scene(b.sensor, ill);
    AbsoluteProfile p = test::profile_for(b, c.scene.width, c.scene.height);
    p.colour = colour_from_sg(b, ill, "T2R");
    const Run r = run(p, c, shoot(b, c.scene, 500), white_Guarnera2018(c.XYZ[18], 600), true);
    std::printf(" %s\n", ill);
    print_run(r);
    INFO(ill);
    CHECK(r.single.relative_Y_error < 0.024);
    CHECK(r.fused.relative_Y_error < 0.024);
    CHECK(mean_nrmse(r.single) < 0.016);
    CHECK(mean_nrmse(r.fused) < 0.013);
    CHECK(mean_nrmse(r.fused) <= r.best_single);
    CHECK(r.fused.metrics.dE00.mean < r.single.metrics.dE00.mean);
  }
}

TEST_CASE("absolute: ColorChecker under D65, A, F2 with the paper's projector training (T1)", "[absolute]") {
  const auto& b = test::bench();
  std::printf("ColorChecker per pixel, colour module from 24 projected ColorChecker colours (T1), eq (16) white:\n");
  for (const char* ill : {"D65", "A", "F2"}) {
    const test::GridScene c = test::chart_scene(b.sensor, ill);
    const AbsoluteProfile p = test::profile_for(b, c.scene.width, c.scene.height);
    const Run r = run(p, c, shoot(b, c.scene, 600), white_Guarnera2018(c.XYZ[18], 600), true);
    std::printf(" %s\n", ill);
    print_run(r);
    INFO(ill);
    CHECK(mean_nrmse(r.fused) <= r.best_single);
    if (std::string(ill) == "D65") {
      CHECK(mean_nrmse(r.single) < 0.016);
      CHECK(mean_nrmse(r.fused) < 0.013);
    } else {  // not the paper's figures (see the header): bounds that catch a regression
      CHECK(mean_nrmse(r.fused) < 0.045);
      CHECK(r.fused.relative_Y_error < 0.08);
    }
  }
}

// The whole absolute chain (Guarnera 2018 eq 4) on the virtual bracket camera, evaluated as
// section 4.1 does: ΔE94, ΔE00 (white per eq 16, or E at the largest luminance), NRMSE per X, Y,
// Z, relative Y error, median absolute error in cd/m². Figures are printed (Table 3/4 layout) and
// held against the paper's Tables 2-4 (paper_table3 / the Experiment (a) case state how).
//
// Three settings:
//  1. equal-tristimulus test stimuli between the training ones (the luminance module, eq 9);
//  2. a ColorChecker under D65, A and F2 with the colour module trained on other reflective
//     colours (the ColorChecker SG patches unlike any of the 24) under the scene's illuminant,
//     T2R (eq 15, the paper's best for its booth scenes) — the brief's thresholds hold here;
//  3. the same chart with the paper's own colour training (24 projected ColorChecker colours,
//     T1). Projected colours are mixtures of three primaries, so M is exact on them and maps
//     this camera's response to broadband (D65, A) or line (F2) spectra with the camera's
//     metamerism: the colour module's floor (matrix_floor.hpp: eq 4 with an exact luminance
//     module) is already 2.5 % (D65), 3.0 % (A), 7.0 % (F2) mean relative Y error, up to 6.7 %
//     (C6 under D65) per patch. The test holds the chain to that floor (it adds < 0.5 % to the
//     relative Y error, < 0.3 % to NRMSE) and to the paper's Table 4 NRMSE under D65; the
//     paper's 2.4 % relative error is Experiment (a)'s, checked in setting 4;
//  4. Experiment (a) of the paper: 8 reflective colour targets, each under 30 projector
//     illuminants, T1 from the projected colours: the mean relative Y error (the paper's
//     2.37 %) and the ΔE of Table 2, white E at the largest luminance.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "absolute_bench.hpp"
#include "matrix_floor.hpp"
#include "test_support.hpp"
#include "tristim/absolute/example.hpp"
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

/// The luminance of each column of `spectra` (cd/m²), the brightest at `top`.
std::vector<double> luminances_up_to(const SpectralData& spectra, double top) {
  std::vector<double> Y;
  for (size_t k = 0; k < spectra.size(); ++k) Y.push_back(test::luminance_sum(spectra, static_cast<int>(k)));
  const double y_max = *std::max_element(Y.begin(), Y.end());
  for (double& y : Y) y *= top / y_max;
  return Y;
}

/// The colour module trained on the ColorChecker SG patches unlike every ColorChecker Classic
/// patch (spectral RMS difference > 0.03), under `illuminant`, photographed at 1/60 s f/8.
Model colour_from_sg(const test::AbsoluteBench& b, const std::string& illuminant, const std::string& transform) {
  const SpectralData keep = sg_unlike_classic();
  const SpectralData spectra = reflected_spectra(keep, illuminant_spd(illuminant));
  const test::GridScene g = test::grid_scene(b.sensor, spectra, luminances_up_to(spectra, 600), 14, 16);
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

namespace {

/// Table 3 of the paper (booth scenes, eq 15 colour profile, statistics without the edge areas):
/// median and mean ΔE94, ΔE00 for a single shot and for 3 exposures. The paper's illuminants
/// D65, ILS (incandescent) and CWF (cool white fluorescent) are matched here by D65, A and F2.
struct PaperTable3 {
  const char* ours;
  const char* paper;
  double single[4], multiple[4];  // ΔE94 median, mean, ΔE00 median, mean
};
constexpr PaperTable3 kTable3[] = {
    {"D65", "D65", {1.8079, 3.0498, 1.4515, 2.3650}, {1.4844, 2.4152, 1.2731, 2.0581}},
    {"A", "ILS", {2.2595, 2.8006, 2.8368, 3.3098}, {2.0524, 2.5414, 2.5255, 2.9773}},
    {"F2", "CWF", {3.1048, 4.3133, 2.5169, 3.8778}, {2.6768, 3.6685, 2.1674, 3.0521}},
};

/// Our median and mean ΔE94 / ΔE00 no higher than the paper's: the virtual camera has no
/// registration error, no spectroradiometer error and a chart instead of a booth scene, so its
/// figures are a lower bound of what the paper measured — being above them is a regression. The
/// maxima are printed, not held: the paper's (8.8-18.8 without edges) come from object edges a
/// chart has few of, ours from the colour module's metamerism on one patch.
void check_against_table(const AbsoluteMetrics& m, const double paper[4], const char* what) {
  const double ours[4] = {m.metrics.dE94.median, m.metrics.dE94.mean, m.metrics.dE00.median, m.metrics.dE00.mean};
  const char* names[4] = {"dE94 median", "dE94 mean", "dE00 median", "dE00 mean"};
  for (int k = 0; k < 4; ++k) {
    INFO(what << " " << names[k] << ": ours " << ours[k] << ", the paper's " << paper[k] << " (tolerance: not above it)");
    CHECK(ours[k] <= paper[k]);
  }
}

}  // namespace

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
    for (const PaperTable3& t : kTable3)  // Table 3 (eq 15 = T2R here): single shot and multiple shots
      if (std::string(t.ours) == ill) {
        std::printf("  Table 3, %s (paper): single dE94 median %.3f mean %.3f, dE00 median %.3f mean %.3f; "
                    "multiple dE94 %.3f %.3f, dE00 %.3f %.3f\n", t.paper, t.single[0], t.single[1], t.single[2],
                    t.single[3], t.multiple[0], t.multiple[1], t.multiple[2], t.multiple[3]);
        check_against_table(r.single, t.single, "single shot vs Table 3");
        check_against_table(r.fused, t.multiple, "fused vs Table 3 multiple shot");
      }
  }
}

/// The colour module's floor per stimulus of a grid scene (matrix_floor.hpp), as patch rows.
PatchMatrix floor_rows(const AbsoluteProfile& p, const VirtualSensor& sensor, const test::GridScene& g) {
  PatchMatrix m(g.ids.size(), 3);
  for (size_t k = 0; k < g.ids.size(); ++k)
    m.row(k) = test::matrix_floor_XYZ(p, sensor.ssf, g.scene.stimuli, k, g.XYZ[k][1]).transpose();
  return m;
}

TEST_CASE("absolute: ColorChecker under D65, A, F2 with the paper's projector training (T1)", "[absolute]") {
  const auto& b = test::bench();
  std::printf("ColorChecker per pixel, colour module from 24 projected ColorChecker colours (T1), eq (16) white:\n");
  for (const char* ill : {"D65", "A", "F2"}) {
    const test::GridScene c = test::chart_scene(b.sensor, ill);
    const AbsoluteProfile p = test::profile_for(b, c.scene.width, c.scene.height);
    const Vec3 white = white_Guarnera2018(c.XYZ[18], 600);
    const AbsoluteMetrics floor = evaluate_absolute(floor_rows(p, b.sensor, c), test::to_patch_matrix(c.XYZ), white);
    const Run r = run(p, c, shoot(b, c.scene, 600), white, true);
    std::printf(" %s\n", ill);
    print("M floor (exact L, patches)", floor);
    print_run(r);
    INFO(ill << ": floor relative Y error " << floor.relative_Y_error << ", NRMSE " << mean_nrmse(floor));
    CHECK(mean_nrmse(r.fused) <= r.best_single);
    CHECK(r.single.relative_Y_error < floor.relative_Y_error + 0.005);
    CHECK(r.fused.relative_Y_error < floor.relative_Y_error + 0.005);
    CHECK(mean_nrmse(r.fused) < mean_nrmse(floor) + 0.003);
    if (std::string(ill) == "D65") {  // Table 4 (booth under D65): 1.5 % single, 1.2 % multiple shots
      CHECK(mean_nrmse(r.single) < 0.016);
      CHECK(mean_nrmse(r.fused) < 0.013);
    }
  }
}

TEST_CASE("absolute: Experiment (a), colour targets under projector illuminants (T1)", "[absolute]") {
  const auto& b = test::bench();
  // 8 ColorChecker reflectances (every third patch) × 30 projector illuminants (mixtures of the
  // three primaries with weights in [0.2, 1.2], from a fixed integer sequence).
  const SpectralData refl = chart_reflectances("cc24"), prim = projector_primaries();
  SpectralData spectra;
  spectra.wavelengths = refl.wavelengths;
  std::uint32_t state = 7;
  auto next = [&] {
    state = state * 1103515245u + 12345u;
    return 0.2 + ((state >> 8) & 0xffff) / 65535.0;
  };
  for (int i = 0; i < 30; ++i) {
    SpectralData ill;
    ill.wavelengths = prim.wavelengths;
    ill.linear = true;
    ill.names = {"P" + std::to_string(i + 1)};
    const double w[3] = {next(), next(), next()};
    ill.values.assign(1, std::vector<double>(prim.wavelengths.size(), 0.0));
    for (int k = 0; k < 3; ++k)
      for (size_t j = 0; j < prim.wavelengths.size(); ++j) ill.values[0][j] += w[k] * prim.values[k][j];
    for (size_t t = 0; t < refl.size(); t += 3) {
      SpectralData one;
      one.wavelengths = refl.wavelengths;
      one.values = {refl.values[t]};
      one.names = {refl.names[t] + "/" + ill.names[0]};
      const SpectralData r = reflected_spectra(one, ill);
      spectra.values.push_back(r.values[0]);
      spectra.names.push_back(r.names[0]);
    }
  }
  const test::GridScene g = test::grid_scene(b.sensor, spectra, luminances_up_to(spectra, 800), 24, 8);
  const AbsoluteProfile p = test::profile_for(b, g.scene.width, g.scene.height);
  double truth_max = 0;
  for (const auto& x : g.XYZ) truth_max = std::max(truth_max, x[1]);
  const Vec3 white = white_equal_energy(truth_max);  // Experiments (a), (c)
  const AbsoluteMetrics floor = evaluate_absolute(floor_rows(p, b.sensor, g), test::to_patch_matrix(g.XYZ), white);
  const Run r = run(p, g, shoot(b, g.scene, 700), white, false);
  std::printf("Experiment (a): %zu samples (8 targets x 30 projector illuminants), patch means, white E at %.0f cd/m2 "
              "(paper, test set: relative Y error 2.37 %%, dE94 mean 1.76, dE00 mean 1.64):\n",
              g.ids.size(), truth_max);
  print("M floor (exact L)", floor);
  print_run(r);
  CHECK(r.single.relative_Y_error < 0.024);
  CHECK(r.fused.relative_Y_error < 0.024);
  CHECK(r.fused.relative_Y_error < floor.relative_Y_error + 0.005);
  // Table 2, test row (T1, single shot): ΔE94 median 1.7428 mean 1.7622 max 3.9997; ΔE00 median
  // 1.6317 mean 1.6352 max 4.5783. Median and mean: ours no higher (check_against_table). The
  // maximum here (about 6.5 / 5.8) is above the paper's: it is the colour module's floor (the
  // same sample with an exact luminance module, "M floor") — one target under one projector mix
  // that this camera sees metamerically —, so it is held to that floor instead: the chain adds
  // less than 0.25 to it.
  const double table2_test[4] = {1.7428, 1.7622, 1.6317, 1.6352};
  check_against_table(r.single, table2_test, "single shot vs Table 2 (test)");
  CHECK(r.single.metrics.dE94.max < floor.metrics.dE94.max + 0.25);
  CHECK(r.single.metrics.dE00.max < floor.metrics.dE00.max + 0.25);
}

// Output lines "BENCH <case> <step> <ms>" and "CASE <case> <text>" are read by scripts/bench.sh
// (native and wasm side by side); the other lines are for a human running it directly.
// Benchmark: surface correction fits (Abed, Berns & Masaoka 2013). Phase I on 140 patches × 31
// wavelengths (the built-in ColorChecker SG, 400-700 nm, mapped onto a planted second
// geometry) for every method; Phase II (the joint fit with a 3×3 matrix) on 140 simulated
// patches; the Table IV simulation. Prints figures; asserts nothing.
#include <algorithm>
#include <cstdio>
#include <string>

#include "bench_util.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/geometry_table.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;
using namespace tristim::bench;

int main() {
  const char* where = build_name();
  std::printf("bench_surface (%s)\n", where);
  const SpectralData sg = chart_reflectances("sg140-2005");
  const MethodChoice truth = parse_choice("saunderson:k1=0.04,k2=0.6,k_ins=0,k1_capture=0.07,k2_capture=0.5,k_ins_capture=0.4");
  const SpectralData target = correct_surface(truth, sg);
  SurfaceFitOptions o;
  o.range_min = 400;
  o.range_max = 700;
  std::printf("\n== Phase I, 140 patches x 31 wavelengths (400-700 nm), best of 5 ==\n");
  for (const char* m : {"scaler", "offset", "scaler-offset", "saunderson"}) {
    MethodChoice start{m, {}, {}};
    if (std::string(m) == "saunderson") start = parse_choice("saunderson:k1=0.04,k2=0.6,k_ins=0");
    SurfaceFitResult r;
    const double t = best_ms(5, [&] { r = fit_surface(start, sg, target, o); });
    std::printf("  %-14s %8.3f ms  %5d evaluations  RMS %.5f -> %.2e  mean dE00 %.3f -> %.4f\n", m, t, r.evaluations,
                r.spectral_rms_before, r.spectral_rms_after, r.summary_dE00_before.mean, r.summary_dE00_after.mean);
    std::printf("BENCH phase1_140x31 %s %.3f\n", m, t);
  }
  {
    SurfaceFitOptions pw = o;
    pw.per_wavelength = true;
    SurfaceFitResult r;
    const double t = best_ms(3, [&] { r = fit_surface(parse_choice("saunderson:k1=0.04,k2=0.6,k_ins=0"), sg, target, pw); });
    std::printf("  %-14s %8.3f ms  %5d evaluations  (per wavelength)\n", "saunderson/λ", t, r.evaluations);
    std::printf("BENCH phase1_140x31 saunderson-per-wavelength %.3f\n", t);
  }

  std::printf("\n== Phase II, 140 simulated patches (Nikon D850, SG row of Table III), best of 5 ==\n");
  GeometryScene scene;
  scene.ssf = camera_ssf("Nikon_D850");
  scene.illuminant = illuminant_spd("D50");
  const GeometryChart chart = simulate_geometry_chart("SG", sg, saunderson_preset("t3-sg-eye-one").geometry,
                                                      saunderson_preset("t3-sg-diffuse").geometry, scene);
  JointFitOptions j;
  j.illuminant = scene.illuminant;
  j.white_RGB = simulate_white_RGB(scene);
  j.white_reflectance = scene.white_reflectance;
  for (const char* m : {"scaler-offset", "saunderson"}) {
    MethodChoice start{m, {}, {}};
    JointFitResult r;
    const double t = best_ms(5, [&] { r = fit_surface_joint_Abed2013(start, chart.camera_RGB, chart.measured, j); });
    std::printf("  %-14s %8.3f ms  %5d evaluations  dE_xyz RMS %.4f -> %.4f\n", m, t, r.evaluations, r.dE_xyz_rms_start,
                r.dE_xyz_rms);
    std::printf("BENCH phase2_140 %s %.3f\n", m, t);
  }

  std::printf("\n== Table IV simulation (4 training charts x 5 methods), best of 3 ==\n");
  GeometryExperiment x;
  const double t_sim = best_ms(3, [&] { x = geometry_experiment_Abed2013(); });
  const double t_table = best_ms(3, [&] { (void)geometry_table_Abed2013(x.training, x.test, x.options); });
  std::printf("  render %8.3f ms   table %8.3f ms\n", t_sim, t_table);
  std::printf("BENCH table4 render %.3f\n", t_sim);
  std::printf("BENCH table4 fit %.3f\n", t_table);
  std::printf("CASE surface Phase I 140x31 and Phase II 140 patches (%s)\n", where);
  return 0;
}

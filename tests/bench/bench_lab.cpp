// Output lines "BENCH <case> <step> <ms>" are read by scripts/bench.sh (native and wasm side by
// side); the other lines are for a human running it directly.
// Benchmark: the colorimetry lab's page actions (issue 45 asks each to run in under 5 s on a
// 2-core machine; measured here, never asserted): rendering a chart DNG (900 × 600 measurement
// pixels, a 1800 × 1200 sensor) with and without noise, a 16-bit TIFF through a gamma OECF, the
// SMI / μ ranking of the 52 cameras, exercise 1 (spectra to colour) and exercise 2 (ten fits with
// leave-one-out and the 1269 Munsell chips), the metamer search over the 1269 Munsell chips (the
// L*-window against comparing all 804 546 pairs) and a metamer constructed with a camera. Prints
// figures; asserts nothing.
#include <cstdio>

#include "bench_util.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/lab/smi.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;
using namespace tristim::bench;

int main() {
  const char* where = build_name();
  std::printf("bench_lab (%s), best of 3, ms\n", where);
  LabRenderOptions o;
  LabRenderFiles f;
  double t = best_ms(3, [&] { f = lab_render_files(o); });
  std::printf("BENCH lab render-dng %.3f\n", t);
  o.shot_gain = 2;
  o.read_noise = 4;
  t = best_ms(3, [&] { f = lab_render_files(o); });
  std::printf("BENCH lab render-dng-noise %.3f\n", t);
  o.oecf = "gamma=2.2";
  t = best_ms(3, [&] { f = lab_render_files(o, "tiff"); });
  std::printf("BENCH lab render-tiff-gamma %.3f\n", t);
  const SpectralData d65 = illuminant_spd("D65");
  std::vector<CameraQuality> q;
  t = best_ms(3, [&] { q = camera_quality_ranking(d65); });
  std::printf("BENCH lab smi-ranking-52 %.3f\n", t);
  SpectraToColour e1;
  t = best_ms(3, [&] { e1 = lab_spectra_to_colour("cc24", "C3"); });
  std::printf("BENCH lab exercise1 %.3f\n", t);
  std::vector<OverfitRow> e2;
  const SpectralData cam = camera_ssf("Canon_EOS_5D_Mark_II");
  t = best_ms(3, [&] { e2 = lab_overfit_exercise(cam, d65); });
  std::printf("BENCH lab exercise2 %.3f\n", t);
  MetamerResult m;
  t = best_ms(3, [&] { m = metamer_pairs(MetamerOptions{}); });
  std::printf("BENCH lab metamers-search %.3f\n", t);
  // The same question by brute force: ΔE00 of every pair (Lab computed once per chip).
  int brute = 0;
  t = best_ms(3, [&] {
    Vec3 w;
    const auto X = reflectances_to_XYZ(munsell_reflectances(), d65, Observer::CIE1931_2, &w);
    std::vector<Vec3> L;
    for (const auto& x : X) L.push_back(XYZ_to_Lab(x, w));
    brute = 0;
    for (size_t i = 0; i < L.size(); ++i)
      for (size_t j = i + 1; j < L.size(); ++j) brute += delta_E_CIE2000(L[i], L[j]) < 0.5;
  });
  std::printf("BENCH lab metamers-all-pairs %.3f\n", t);
  std::printf("(metamer search: %d of %d pairs compared, %d matching; all pairs: %d matching)\n", m.compared, m.all_pairs,
              m.matching, brute);
  MetamerOptions mc;
  mc.camera = "Canon_EOS_5D_Mark_II";
  t = best_ms(3, [&] { m = construct_metamer(mc, "5R5/6"); });
  std::printf("BENCH lab metamers-construct-camera %.3f\n", t);
  // Exercises 3-5 as the page runs them (exercise 5: one light, both trainings).
  ShenExercise e3;
  t = best_ms(1, [&] { e3 = lab_shen_exercise(cam); });
  std::printf("BENCH lab exercise3-shen %.3f\n", t);
  t = best_ms(1, [&] { lab_table4_exercise(); });
  std::printf("BENCH lab exercise4-table4 %.3f\n", t);
  t = best_ms(1, [&] { lab_exposure_exercise(cam, d65); });
  std::printf("BENCH lab exercise5-exposure %.3f\n", t);
  t = best_ms(1, [&] { lab_guarnera_table4("Canon_EOS_5D_Mark_II", {"A"}); });
  std::printf("BENCH lab exercise5-table4-one-light %.3f\n", t);
  std::printf("(%zu bytes of DNG/TIFF, %zu cameras ranked, %zu exercise-2 rows)\n", f.dng.size(), q.size(), e2.size());
  return 0;
}

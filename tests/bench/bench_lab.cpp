// Output lines "BENCH <case> <step> <ms>" are read by scripts/bench.sh (native and wasm side by
// side); the other lines are for a human running it directly.
// Benchmark: the colorimetry lab's page actions (issue 45 asks each to run in under 5 s on a
// 2-core machine; measured here, never asserted): rendering a chart DNG (900 × 600 measurement
// pixels, a 1800 × 1200 sensor) with and without noise, a 16-bit TIFF through a gamma OECF, the
// SMI / μ ranking of the 52 cameras, exercise 1 (spectra to colour) and exercise 2 (ten fits with
// leave-one-out and the 1269 Munsell chips). Prints figures; asserts nothing.
#include <cstdio>

#include "bench_util.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/lab/smi.hpp"
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

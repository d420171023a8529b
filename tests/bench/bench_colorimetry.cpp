// Benchmark: reference charts, file parsing and the virtual camera. Prints figures, asserts nothing.
#include <cstdio>
#include <string>

#include "bench_util.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/data.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace {
/// The first call (built-in tables parsed once; in wasm, baseline code), then the mean of n calls.
template <class F>
void time_it(const char* step, const char* what, int n, F&& f) {
  using namespace tristim::bench;
  const double first = time_ms(f);
  const auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) f();
  const double ms = ms_since(t0) / n;
  std::printf("  %-52s %9.3f ms  (first call %.3f ms)\n", what, ms, first);
  std::printf("BENCH colorimetry %s %.3f\n", step, ms);
}
}  // namespace

int main() {
  using namespace tristim;
  std::printf("CASE colorimetry reference charts from spectra, a spectral CSV, the virtual camera (mean of n calls after the first)\n");
  time_it("ref_sg140_D50", "reference_chart(sg140, D50, 1931)", 20,
          [] { (void)reference_chart("sg140", "D50", Observer::CIE1931_2); });
  time_it("ref_cc24_D4500_1964", "reference_chart(cc24, D4500, 1964)", 50,
          [] { (void)reference_chart("cc24", "D4500", Observer::CIE1964_10); });
  const std::string sg(builtin_file("charts/colorcheckerSG_after_nov2014_reflectance_380-730_10nm.csv"));
  time_it("read_sg_csv_45KB", "read_patch_file(SG spectral CSV, 45 KB)", 50,
          [&] { (void)read_patch_file(sg, "sg.csv"); });
  const SpectralData ssf = camera_ssf("Canon_EOS_5D_Mark_II"), refl = chart_reflectances("sg140"), ill = illuminant_spd("D65");
  SimulationOptions o;
  o.noise_sigma = 0.01;
  time_it("simulate_5D2_sg140", "simulate_camera_RGB(5D Mark II, sg140, D65, noise)", 100,
          [&] { (void)simulate_camera_RGB(ssf, refl, ill, o); });
  return 0;
}

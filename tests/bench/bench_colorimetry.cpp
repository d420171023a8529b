// Benchmark: reference charts, file parsing and the virtual camera. Prints figures, asserts nothing.
#include <chrono>
#include <cstdio>
#include <string>

#include "tristim/chart/reference.hpp"
#include "tristim/data.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace {
template <class F>
void time_it(const char* what, int n, F&& f) {
  f();  // warm caches (built-in tables are parsed once)
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) f();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / n;
  std::printf("%-55s %9.3f ms\n", what, ms);
}
}  // namespace

int main() {
  using namespace tristim;
  time_it("reference_chart(sg140, D50, 1931)", 20, [] { (void)reference_chart("sg140", "D50", Observer::CIE1931_2); });
  time_it("reference_chart(cc24, D4500, 1964)", 50, [] { (void)reference_chart("cc24", "D4500", Observer::CIE1964_10); });
  const std::string sg(builtin_file("charts/colorcheckerSG_after_nov2014_reflectance_380-730_10nm.csv"));
  time_it("read_patch_file(SG spectral CSV, 45 KB)", 50, [&] { (void)read_patch_file(sg, "sg.csv"); });
  const SpectralData ssf = camera_ssf("Canon_EOS_5D_Mark_II"), refl = chart_reflectances("sg140"), ill = illuminant_spd("D65");
  SimulationOptions o;
  o.noise_sigma = 0.01;
  time_it("simulate_camera_RGB(5D Mark II, sg140, D65, noise)", 100, [&] { (void)simulate_camera_RGB(ssf, refl, ill, o); });
  return 0;
}

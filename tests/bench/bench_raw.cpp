// Benchmark: decode + calibration + chart sampling on the Passport DNG, the 30D CR2 and synthetic
// 24 MP / 50 MP uncompressed DNGs written by tristim::write_dng. Prints figures, asserts nothing.
// In wasm this program runs with a 1 GiB heap limit (tests/bench/CMakeLists.txt): the 50 MP case
// (file bytes, LibRaw's raster, linear RGB, plus full-size dark and flat frames) must fit.
// Output lines "BENCH <case> <step> <ms>" and "PEAK <case> <MiB>" are read by scripts/bench.sh.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "test_files.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/chart/layout.hpp"
#include "dng_writer.hpp"
#include "tristim/error.hpp"
#include "tristim/capture/raw.hpp"

using namespace tristim;
using namespace tristim::bench;

namespace {

std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("'" + path + "' not found (tests/data/SOURCES.md says where it comes from)");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  return {s.begin(), s.end()};
}

std::vector<std::uint8_t> synthetic_dng(int w, int h) {
  std::vector<std::uint16_t> v(static_cast<size_t>(w) * h);
  std::uint32_t seed = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      seed = seed * 1664525u + 1013904223u;
      const int base = 600 + ((x / (w / 6)) + 6 * (y / (h / 4))) * 500;  // a 6×4 "chart"
      v[static_cast<size_t>(y) * w + x] = static_cast<std::uint16_t>(base + (seed >> 28));
    }
  DngWriteOptions o;
  o.black = 512;
  o.white = 16383;
  return write_dng(v, w, h, o);
}

void run_case(const std::string& name, std::vector<std::uint8_t> bytes, double file_mb, bool quiet = false) {
  RawImage img;
  const double t_decode = time_ms([&] { img = decode_raw(bytes); });
  std::vector<std::uint8_t>().swap(bytes);
  // Calibration: a synthetic dark frame (constant 2 DN) and flat (constant 1000 DN) of the same
  // size, per-pixel dark subtraction, per-pixel flat field, a fall-off fit, and a full apply.
  RawImage dark = img, flat = img;
  std::fill(dark.rgb.begin(), dark.rgb.end(), 2.0f);
  std::fill(flat.rgb.begin(), flat.rgb.end(), 1000.0f);
  std::fill(flat.saturated.begin(), flat.saturated.end(), 0);
  FrameCalibration cal;
  const double t_cal = time_ms([&] {
    cal.dark = average_dark_frames({&dark});
    cal.flat = make_flat_field(flat, &*cal.dark);
  });
  const double t_falloff = time_ms([&] { fit_falloff_Guarnera2018(flat, &*cal.dark); });
  { RawImage().rgb.swap(dark.rgb); RawImage().rgb.swap(flat.rgb); }
  // First call: what a CLI run pays (natively the output is fresh memory from the system, page
  // faults included; wasm reuses its grown heap). Again: the same call with memory that was used
  // before, i.e. the computation alone in both builds.
  const double t_apply = time_ms([&] { RawImage out = apply_calibration(img, cal); (void)out; });
  const double t_apply_again = time_ms([&] { RawImage out = apply_calibration(img, cal); (void)out; });
  LayoutOptions lo;
  lo.chart = "cc24";
  const double W = img.width, H = img.height;
  const std::array<double, 8> corners = {0.1 * W, 0.1 * H, 0.9 * W, 0.12 * H, 0.88 * W, 0.9 * H, 0.12 * W, 0.88 * H};
  ChartSample s;
  const double t_sample = time_ms([&] { s = sample_chart(img, lo, corners, {}, &cal); });
  if (quiet) return;
  std::printf("CASE %s %dx%d sensor, %dx%d measurement, %.1f MB file, %d px/patch\n", name.c_str(),
              img.meta.sensor_width, img.meta.sensor_height, img.width, img.height, file_mb, s.patches[0].n);
  std::printf("BENCH %s decode %.1f\n", name.c_str(), t_decode);
  std::printf("BENCH %s dark+flat %.1f\n", name.c_str(), t_cal);
  std::printf("BENCH %s falloff_fit %.1f\n", name.c_str(), t_falloff);
  std::printf("BENCH %s apply_calibration %.1f\n", name.c_str(), t_apply);
  std::printf("BENCH %s apply_calibration_again %.1f\n", name.c_str(), t_apply_again);
  std::printf("BENCH %s sample_cc24 %.1f\n", name.c_str(), t_sample);
  std::printf("BENCH %s total %.1f\n", name.c_str(), t_decode + t_cal + t_falloff + t_apply + t_sample);
  std::printf("PEAK %s %.0f\n", name.c_str(), peak_mib());
  std::fflush(stdout);
}

}  // namespace

int main() {
  auto data_file = [](const char* f) { return tristim::test::test_file_path(TRISTIM_SOURCE_DIR, f); };
  try {
    auto dng = read_file(data_file(tristim::test::passport_dng));
    // Warm-up: V8 runs wasm first in its baseline compiler and swaps in optimised code only for
    // later calls (no on-stack replacement), so a first decode in node/the browser is slower
    // than these steady-state figures (about 2x for the Passport DNG).
    for (int i = 0; i < 2; ++i) run_case("warm-up", dng, 0, true);
    run_case("passport_dng_2.2MP", dng, dng.size() / 1e6);
    auto cr2 = read_file(data_file(tristim::test::debian::canon_30d_cr2));
    run_case("canon30d_cr2_8.2MP", cr2, cr2.size() / 1e6);
    {
      auto b = synthetic_dng(6000, 4000);
      const double mb = b.size() / 1e6;
      run_case("synthetic_dng_24MP", std::move(b), mb);
    }
    {
      auto b = synthetic_dng(8688, 5792);
      const double mb = b.size() / 1e6;
      run_case("synthetic_dng_50MP", std::move(b), mb);
    }
  } catch (const Error& e) {
    std::printf("ERROR %s: %s\n", e.code_name(), e.what());
    return 1;
  } catch (const std::exception& e) {
    std::printf("ERROR %s (peak %.0f MiB)\n", e.what(), peak_mib());
    return 1;
  }
  return 0;
}

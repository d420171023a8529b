// Benchmark: automatic chart detection (issue 12) on the Passport DNG and on synthetic scenes of
// the size of a 24 MP RAW's half-resolution image (3000 × 2000) and of a 12 MP image
// (4000 × 3000), ColorChecker Classic and Digital SG. Target: < 300 ms natively, < 2× in wasm.
// Stage times come from the detector's progress callback. Prints figures, asserts nothing.
// Output lines "BENCH <case> <step> <ms>" and "PEAK <case> <MiB>" are read by scripts/bench.sh.
// Then issue 48's failure kinds (chart_scene.hpp failure_kinds: tilted charts with glare, a cast
// shadow or a grid-like object beside them, small charts, an open Passport, a chart cut by the
// frame, strong perspective, phone-like JPEGs, SG, no chart), a few scenes each: found, wrong
// orientations, false positives, corner error and found after one click, per kind, before and after
// the cut-chart step ("KIND" lines;
// `detect_testset --kinds all` runs the full set, docs/detection.md has its figures).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "test_files.hpp"
#include "chart_scene.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

using namespace tristim;
using namespace tristim::bench;

namespace {

// Median over `runs` of the total and of each stage (time from one stage's start to the next's).
void run_case(const std::string& name, const RawImage& img, const std::string& chart, int runs = 3) {
  std::map<std::string, std::vector<double>> stages;
  std::vector<std::string> order;
  ChartCandidate best;
  for (int r = 0; r < runs; ++r) {
    DetectOptions o;
    o.charts = {chart};
    const auto t0 = Clock::now();
    auto last = t0;
    std::string stage = "start";
    std::map<std::string, double> sum;  // this run's time per stage (stages recur per grid)
    auto close = [&](const std::string& next) {
      const auto now = Clock::now();
      if (stage != "start") {
        if (!sum.count(stage) && r == 0) order.push_back(stage);
        sum[stage] += std::chrono::duration<double, std::milli>(now - last).count();
      }
      stage = next;
      last = now;
    };
    o.progress = [&](const std::string& s, double) {
      if (s != stage) close(s);
    };
    try {
      best = detect_charts(img, o).front();
    } catch (const Error& e) {
      std::printf("ERROR %s: %s\n", name.c_str(), e.what());
      return;
    }
    close("end");
    for (const auto& kv : sum) stages[kv.first].push_back(kv.second);
    stages["total"].push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  order.push_back("total");
  std::printf("CASE %s %dx%d, %s found with confidence %.2f, corner 1 at (%.1f, %.1f)\n", name.c_str(), img.width,
              img.height, best.chart.c_str(), best.confidence, best.corners[0], best.corners[1]);
  for (const auto& s : order) {
    auto v = stages[s];
    std::sort(v.begin(), v.end());
    std::printf("BENCH %s %s %.1f\n", name.c_str(), s.c_str(), v[v.size() / 2]);
  }
  std::printf("PEAK %s %.0f\n", name.c_str(), peak_mib());
  std::fflush(stdout);
}

}  // namespace

int main() {
  try {
    const std::string dng_path = tristim::test::test_file_path(TRISTIM_SOURCE_DIR, tristim::test::passport_dng);
    std::ifstream in(dng_path, std::ios::binary);
    if (!in) throw Error(ErrorCode::InvalidArgument, "'" + dng_path + "' not found");
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string bytes = ss.str();
    const std::vector<RawImage> photos = background_photos(TRISTIM_SOURCE_DIR);
    std::vector<const RawImage*> ptrs;
    for (const auto& p : photos) ptrs.push_back(&p);
    {
      const RawImage dng = decode_raw(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      run_case("warm-up", dng, "passport", 1);  // wasm: let V8 tier up first
      run_case("passport_dng", dng, "passport", 5);
    }
    for (const auto& size : {std::array<int, 2>{3000, 2000}, std::array<int, 2>{4000, 3000}})
      for (const std::string chart : {"cc24", "sg140"}) {
        SceneSpec spec;
        spec.chart = chart;
        spec.width = size[0];
        spec.height = size[1];
        spec.area_fraction = 0.08;
        spec.tilt_deg = 25;
        spec.rotation_deg = 17;
        spec.blur_sigma = 1.2;
        spec.photo_background = !ptrs.empty();
        spec.seed = 4242;
        const ChartScene scene = render_chart_scene(spec, ptrs);
        run_case(chart + "_" + std::to_string(size[0] * size[1] / 1000000) + "MP", scene.image, chart);
        if (chart == "cc24" && size[0] == 3000) {  // the same scene as a phone's 8-bit sRGB JPEG
          spec.phone = true;
          run_case("cc24_phone_" + std::to_string(size[0] * size[1] / 1000000) + "MP", render_chart_scene(spec, ptrs).image, chart);
        }
      }
    // Before and after: the detector as it was before issue 48's cut-chart and finer-pass steps
    // (DetectOptions::cut_charts and finer_pass false) and as it is now.
    DetectOptions before;
    before.cut_charts = false;
    before.finer_pass = false;
    std::printf("\nissue 48's failure kinds, 4 scenes each (1200 x 800), BEFORE (cut charts refused, no finer pass):\n");
    print_failure_kinds(run_failure_kinds({}, 4, 1, 1200, ptrs, false, before));
    std::printf("\nissue 48's failure kinds, 4 scenes each (1200 x 800), NOW:\n");
    print_failure_kinds(run_failure_kinds({}, 4, 1, 1200, ptrs, false));
  } catch (const std::exception& e) {
    std::printf("ERROR %s (peak %.0f MiB)\n", e.what(), peak_mib());
    return 1;
  }
  return 0;
}

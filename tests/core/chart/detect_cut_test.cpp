// A chart partly cut by the frame (issue 48): sampling the patches inside the image with the
// corners outside it (SampleOptions::partial), detection of such a chart with the missing patches
// named, and the CLI on a DNG of one: `tristim detect` lists them, `tristim sample` samples the rest
// and `tristim fit` trains on those.
#include <algorithm>
#include <cmath>
#include <set>

#include "chart_scene.hpp"
#include "test_support.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/error.hpp"
#ifndef __EMSCRIPTEN__
#include <unistd.h>

#include <cstdlib>
#include <sstream>

#include "dng_writer.hpp"
#include "shell.hpp"
#include "tristim/io/json.hpp"
#endif

using namespace tristim;
using tristim::test::code_of;

namespace {

// The scene of a chart whose grid runs off the right edge of a 900 × 600 frame.
ChartScene cut_scene(const std::string& chart) {
  SceneSpec s = plain_scene_spec(chart, 15, 32);
  s.area_fraction = 0.25;
  s.cx = 0.92;
  s.allow_cut = true;
  return render_chart_scene(s);
}

std::set<std::string> ids_of(const std::vector<PatchSample>& patches) {
  std::set<std::string> out;
  for (const auto& p : patches) out.insert(p.id);
  return out;
}

}  // namespace

TEST_CASE("partial sampling: corners outside the image, the patches outside named, the rest as before",
          "[chart][cut]") {
  // A planted cc24 image (patch i has value 10 + i in every channel) of 200 × 100 px with the grid
  // at x 0..300: the sample areas of columns 5 and 6 (from x 207) are outside.
  RawImage img;
  img.width = 200;
  img.height = 100;
  img.rgb.assign(size_t(img.width) * img.height * 3, 1.f);
  img.saturated.assign(size_t(img.width) * img.height, 0);
  img.meta.saturation = {1000, 1000, 1000};
  LayoutOptions lo;
  lo.chart = "cc24";
  const std::array<double, 8> corners{0, 0, 300, 0, 300, 100, 0, 100};
  const ChartLayout layout = chart_layout(lo);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (size_t k = 0; k < layout.patches.size(); ++k) {
        const auto& p = layout.patches[k];
        const double u = (x + 0.5) / 300, v = (y + 0.5) / 100;
        if (u >= p.u0 && u < p.u1 && v >= p.v0 && v < p.v1)
          for (int c = 0; c < 3; ++c) img.rgb[(size_t(y) * img.width + x) * 3 + c] = float(10 + k);
      }
  CHECK(code_of([&] { sample_chart(img, lo, corners); }) == ErrorCode::CornersOutside);
  SampleOptions partial;
  partial.partial = true;
  const ChartSample s = sample_chart(img, lo, corners, partial);
  const std::vector<std::string> missing{"A5", "A6", "B5", "B6", "C5", "C6", "D5", "D6"};
  CHECK(s.missing == missing);
  REQUIRE(s.patches.size() == 16);
  for (const auto& p : s.patches) {
    const size_t k = static_cast<size_t>(std::find_if(layout.patches.begin(), layout.patches.end(),
                                                      [&](const PatchCell& c) { return c.id == p.id; }) -
                                         layout.patches.begin());
    INFO(p.id);
    CHECK(p.mean[1] == Approx(10.0 + k).margin(1e-9));
    CHECK(p.flags.empty());
  }
  // Corners inside: the same as a whole sampling, nothing missing.
  const std::array<double, 8> inside{10, 5, 190, 5, 190, 95, 10, 95};
  const ChartSample whole = sample_chart(img, lo, inside), whole_partial = sample_chart(img, lo, inside, partial);
  CHECK(whole_partial.missing.empty());
  REQUIRE(whole_partial.patches.size() == whole.patches.size());
  for (size_t k = 0; k < whole.patches.size(); ++k) CHECK(whole_partial.patches[k].mean == whole.patches[k].mean);
  // Still refused: no patch inside, crossed corners, a corner not finite.
  CHECK(code_of([&] { sample_chart(img, lo, {300, 0, 600, 0, 600, 100, 300, 100}, partial); }) == ErrorCode::CornersOutside);
  CHECK(code_of([&] { sample_chart(img, lo, {0, 0, 300, 100, 300, 0, 0, 100}, partial); }) == ErrorCode::CornersCrossed);
  CHECK(code_of([&] { sample_chart(img, lo, {0, 0, NAN, 0, 300, 100, 0, 100}, partial); }) == ErrorCode::CornersOutside);
}

TEST_CASE("a chart cut by the frame: found, its corners outside the image, the missing patches named",
          "[detect][cut]") {
  for (const std::string chart : {"cc24", "sg140"}) {
    INFO(chart);
    const ChartScene scene = cut_scene(chart);
    REQUIRE(scene.cut);
    const std::vector<ChartCandidate> found = detect_charts(scene.image);
    REQUIRE(!found.empty());
    const ChartCandidate& c = found.front();
    CHECK(c.chart == chart);
    CHECK(c.confidence >= 0.5);
    CHECK(max_corner_error(c.corners, scene.corners) < 0.5);
    // The missing patches are those whose sample area leaves the image at the true corners.
    LayoutOptions lo;
    lo.chart = chart;
    SampleOptions partial;
    partial.partial = true;
    const ChartSample truth = sample_chart(scene.image, lo, scene.corners, partial);
    REQUIRE(!truth.missing.empty());
    CHECK(c.missing == truth.missing);
    CHECK(c.patches.size() + c.missing.size() == chart_layout(lo).patches.size());
    // The visible patches sampled at the found corners agree with their sampling at the truth.
    const ChartSample at_found = sample_chart(scene.image, lo, c.corners, partial);
    REQUIRE(ids_of(at_found.patches) == ids_of(truth.patches));
    for (size_t k = 0; k < truth.patches.size(); ++k)
      for (int ch = 0; ch < 3; ++ch)
        CHECK(at_found.patches[k].mean[ch] == Approx(truth.patches[k].mean[ch]).epsilon(0.01).margin(2.0));
  }
}

#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
TEST_CASE("CLI on a cut chart: detect names the missing patches, sample and fit use the rest", "[detect][cut][cli]") {
  const ChartScene scene = cut_scene("cc24");
  // The scene's half-resolution image as an RGGB mosaic (each pixel one 2×2 block).
  const RawImage& im = scene.image;
  std::vector<std::uint16_t> cfa(size_t(im.width) * 2 * im.height * 2);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const auto at = [&](int c) { return static_cast<std::uint16_t>(std::lround(std::clamp(double(im.at(x, y, c)), 0.0, 16383.0))); };
      const size_t row0 = size_t(2 * y) * im.width * 2, row1 = row0 + size_t(im.width) * 2;
      cfa[row0 + 2 * x] = at(0), cfa[row0 + 2 * x + 1] = at(1), cfa[row1 + 2 * x] = at(1), cfa[row1 + 2 * x + 1] = at(2);
    }
  DngWriteOptions o;
  o.white = 16383;
  const test::ScratchDir scratch("detect_cut");
  const std::string& d = scratch.d;
  const auto bytes = write_dng(cfa, im.width * 2, im.height * 2, o);
  test::spit(d + "cut.dng", std::string(bytes.begin(), bytes.end()));
  const std::string cli = TRISTIM_CLI;
  const json::Value j = json::parse(test::run_shell(cli + " detect " + d + "cut.dng"));
  REQUIRE(j.at("candidates").size() >= 1);
  const json::Value& c = j.at("candidates").as_array().front();
  CHECK(c.at("chart").as_string() == "cc24");
  LayoutOptions lo;
  SampleOptions partial;
  partial.partial = true;
  const ChartSample truth = sample_chart(im, lo, scene.corners, partial);
  std::vector<std::string> missing;
  for (const auto& m : c.at("missing").as_array()) missing.push_back(m.as_string());
  CHECK(missing == truth.missing);
  // sample (detecting the chart) writes the visible patches only; fit trains on them with the
  // reference's rows of those patches.
  const std::string csv = test::run_shell(cli + " sample " + d + "cut.dng --chart cc24 2>/dev/null");
  size_t rows = 0;
  for (char ch : csv) rows += ch == '\n';
  CHECK(rows == 1 + truth.patches.size());
  for (const auto& id : truth.missing) CHECK(csv.find("\n" + id + ",") == std::string::npos);
  test::spit(d + "rgb.csv", csv);
  const std::string ref = test::run_shell(cli + " reference --chart cc24 --illuminant D65");
  std::string kept;
  std::istringstream lines(ref);
  for (std::string line; std::getline(lines, line);)
    if (std::none_of(truth.missing.begin(), truth.missing.end(),
                     [&](const std::string& id) { return line.rfind(id + ",", 0) == 0; }))
      kept += line + "\n";
  test::spit(d + "xyz.csv", kept);
  const json::Value fit = json::parse(test::run_shell(cli + " fit --rgb " + d + "rgb.csv --xyz " + d + "xyz.csv --model matrix-3x3 2>/dev/null"));
  CHECK(fit.at("training").at("patches").as_number() == double(truth.patches.size()));
}
#endif

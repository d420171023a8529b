// Detection helped and explained (issue 48): a miss says why; a seed point or a rough box runs
// detection again within that region; phone-like 8-bit sRGB images are decoded before the fit.
#include <cmath>
#include <string>

#include "chart_scene.hpp"
#include "test_support.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

using namespace tristim;
using tristim::test::code_of;

namespace {

std::string why_of(const RawImage& image, const DetectOptions& o = {}) {
  try {
    detect_charts(image, o);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::ChartNotFound) return e.what();
    throw;
  }
  return "";
}

SceneSpec tiny_chart() {
  // A Classic of 0.2 % of a 2400 × 1600 frame (patches ~14 px across, ~7 px in the 1600 px
  // working image): too small for the automatic passes.
  SceneSpec s = plain_scene_spec("cc24", 8, 4801);
  s.width = 2400, s.height = 1600, s.area_fraction = 0.002;
  s.tilt_deg = 10, s.tilt_axis_deg = 0, s.cx = 0.7, s.cy = 0.35;
  return s;
}

}  // namespace

TEST_CASE("a miss says why: no grid, or a grid whose colours fit no chart", "[detect][help]") {
  SceneSpec none = tiny_chart();
  none.area_fraction = 1e-5;
  none.width = 900, none.height = 600;
  const std::string no_grid = why_of(render_chart_scene(none).image);
  INFO(no_grid);
  CHECK((no_grid.find("form no grid") != std::string::npos || no_grid.find("no flat region") != std::string::npos));
  // A Classic's grid looked for as a Digital SG: a 4×6 lattice whose colours fit no SG.
  SceneSpec cc = tiny_chart();
  cc.width = 900, cc.height = 600, cc.area_fraction = 0.15;
  DetectOptions sg;
  sg.charts = {"sg140"};
  const std::string wrong = why_of(render_chart_scene(cc).image, sg);
  INFO(wrong);
  CHECK(wrong.find("a grid of 4×6") != std::string::npos);
}

TEST_CASE("a seed near a chart too small to find finds it, and so does a rough box", "[detect][help]") {
  const ChartScene scene = render_chart_scene(tiny_chart());
  const std::string why = why_of(scene.image);
  INFO("automatic: " << why);
  REQUIRE(!why.empty());  // the automatic detector misses it (else the test shows nothing)
  double cx = 0, cy = 0;
  for (int k = 0; k < 4; ++k) cx += scene.corners[2 * k] / 4, cy += scene.corners[2 * k + 1] / 4;
  DetectOptions seeded;
  seeded.seed = {cx + 20, cy - 15};  // a click near the chart, not on its centre
  const auto found = detect_charts(scene.image, seeded);
  REQUIRE(!found.empty());
  CHECK(found[0].chart == "cc24");
  CHECK(max_corner_error(found[0].corners, scene.corners) < 0.5);
  CHECK(found[0].confidence > 0.8);
  // A rough box that cuts the chart's outer patches a little (it is enlarged by a tenth).
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (int k = 0; k < 4; ++k)
    x0 = std::min(x0, scene.corners[2 * k]), x1 = std::max(x1, scene.corners[2 * k]),
    y0 = std::min(y0, scene.corners[2 * k + 1]), y1 = std::max(y1, scene.corners[2 * k + 1]);
  DetectOptions boxed;
  boxed.box = {x0 + 3, y0 - 10, x1 + 25, y1 - 2};
  const auto in_box = detect_charts(scene.image, boxed);
  REQUIRE(!in_box.empty());
  CHECK(max_corner_error(in_box[0].corners, scene.corners) < 0.5);
  // A seed far from the chart finds nothing, and says where it looked.
  DetectOptions far;
  far.seed = {100, 1500};
  const std::string away = why_of(scene.image, far);
  CHECK(away.find("no chart near the seed (100, 1500)") == 0);
}

TEST_CASE("seed and box: bad values are refused naming the option", "[detect][help][bad]") {
  SceneSpec s = tiny_chart();
  s.width = 300, s.height = 200;
  const RawImage image = render_chart_scene(s).image;
  auto code = [&](std::vector<double> seed, std::vector<double> box) {
    DetectOptions o;
    o.seed = std::move(seed);
    o.box = std::move(box);
    return code_of([&] { detect_charts(image, o); });
  };
  CHECK(code({1, 2, 3}, {}) == ErrorCode::InvalidArgument);
  CHECK(code({-5, 10}, {}) == ErrorCode::InvalidArgument);
  CHECK(code({300, 10}, {}) == ErrorCode::InvalidArgument);
  CHECK(code({NAN, 10}, {}) == ErrorCode::InvalidArgument);
  CHECK(code({10, 10}, {0, 0, 100, 100}) == ErrorCode::InvalidArgument);
  CHECK(code({}, {400, 300, 500, 400}) == ErrorCode::InvalidArgument);  // outside the image
  CHECK(code({}, {10, 10, 12, 12}) == ErrorCode::InvalidArgument);      // under 16 px
  CHECK(code({}, {1, 2}) == ErrorCode::InvalidArgument);
}

TEST_CASE("a phone-like 8-bit sRGB image: decoded before the fit, found like the linear one", "[detect][help]") {
  for (const std::string chart : {"cc24", "sg140"}) {
    SceneSpec s = tiny_chart();
    s.chart = chart;
    s.width = 900, s.height = 600, s.area_fraction = 0.2, s.rotation_deg = 125;
    s.phone = true;
    const ChartScene phone = render_chart_scene(s);
    REQUIRE(phone.image.meta.encoding == "stored");
    DetectOptions o;
    o.charts = {chart};
    const auto found = detect_charts(phone.image, o);
    INFO(chart);
    REQUIRE(!found.empty());
    CHECK(max_corner_error(found[0].corners, phone.corners) < 0.5);
    CHECK(found[0].orientation == 90);
    // The same values read as linear light (what the detector did before): no chart's colours.
    RawImage as_linear = phone.image;
    as_linear.meta.encoding = "linear";
    CHECK(code_of([&] { detect_charts(as_linear, o); }) == ErrorCode::ChartNotFound);
  }
}

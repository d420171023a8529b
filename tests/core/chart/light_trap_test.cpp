// In-scene light trap (Abed 2013 App. C step 1): its mean is subtracted per channel before sampling.
#include <catch2/catch.hpp>

#include "test_support.hpp"
#include "tristim/chart/light_trap.hpp"

using namespace tristim;

namespace {

// 160 × 100 image: flare + a chart of two patches (x 20-100, y 20-60: left half (10, 20, 30)·k,
// right half 4× brighter) and a light trap (x 120-150, y 30-70) that returns the flare alone.
RawImage scene(const std::array<double, 3>& flare, double dark_level) {
  RawImage img;
  img.width = 160;
  img.height = 100;
  img.meta.make = "tristim";
  img.meta.model = "Synthetic";
  img.meta.saturation = {16000, 16000, 16000};
  img.rgb.assign(size_t(img.width) * img.height * 3, 0.f);
  img.saturated.assign(size_t(img.width) * img.height, 0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) {
        double v = 500;  // the surround
        if (x >= 20 && x < 100 && y >= 20 && y < 60) v = (x < 60 ? 1.0 : 4.0) * 100 * (c + 1);
        if (x >= 120 && x < 150 && y >= 30 && y < 70) v = 0;  // the trap: no light comes back
        img.rgb[(size_t(y) * img.width + x) * 3 + c] = static_cast<float>(v + flare[c] + dark_level);
      }
  return img;
}

const std::array<double, 8> kChart = {20, 20, 100, 20, 100, 60, 20, 60};
const std::array<double, 8> kTrap = {120, 30, 150, 30, 150, 70, 120, 70};

LayoutOptions two_patches() {
  LayoutOptions lo;
  lo.chart = "custom";
  lo.rows = 1;
  lo.columns = 2;
  return lo;
}

}  // namespace

TEST_CASE("light trap flare is measured and subtracted before sampling", "[chart][light_trap]") {
  const std::array<double, 3> flare = {40, 55, 70};
  const RawImage img = scene(flare, 0);
  const LightTrap trap = measure_light_trap(img, kTrap);
  for (int c = 0; c < 3; ++c) CHECK(trap.mean[c] == Approx(flare[c]).margin(1e-4));
  CHECK(trap.n > 100);
  const ChartSample raw = sample_chart(img, two_patches(), kChart);
  const FrameCalibration cal = with_light_trap(FrameCalibration{}, trap);
  const ChartSample clean = sample_chart(img, two_patches(), kChart, {}, &cal);
  for (int c = 0; c < 3; ++c) {
    CHECK(raw.patches[0].mean[c] == Approx(100 * (c + 1) + flare[c]).margin(1e-3));
    CHECK(clean.patches[0].mean[c] == Approx(100 * (c + 1)).margin(1e-3));
    CHECK(clean.patches[1].mean[c] == Approx(400 * (c + 1)).margin(1e-3));
  }
  // The flare is an additive level: the chart's 1:4 ratio comes back only once it is removed.
  CHECK(clean.patches[1].mean[0] / clean.patches[0].mean[0] == Approx(4).epsilon(1e-6));
  CHECK(raw.patches[1].mean[0] / raw.patches[0].mean[0] < 3.5);
}

TEST_CASE("light trap is measured after the dark frame, before the flat field", "[chart][light_trap]") {
  const std::array<double, 3> flare = {12, 18, 25};
  const RawImage img = scene(flare, 30);  // a dark level of 30 DN on top
  FrameCalibration cal;
  DarkFrame dark;
  dark.width = img.width;
  dark.height = img.height;
  dark.frames = 1;
  dark.make = img.meta.make;
  dark.model = img.meta.model;
  dark.rgb.assign(img.rgb.size(), 30.f);
  dark.mean = {30, 30, 30};
  cal.dark = dark;
  FlatField flat;  // a gain of 2 everywhere: must not scale the trap
  flat.width = img.width;
  flat.height = img.height;
  flat.make = img.meta.make;
  flat.model = img.meta.model;
  flat.gain.assign(img.rgb.size(), 2.f);
  cal.flat = flat;
  const LightTrap trap = measure_light_trap(img, kTrap, {}, &cal);
  for (int c = 0; c < 3; ++c) CHECK(trap.mean[c] == Approx(flare[c]).margin(1e-4));
  const FrameCalibration full = with_light_trap(cal, trap);
  const ChartSample s = sample_chart(img, two_patches(), kChart, {}, &full);
  for (int c = 0; c < 3; ++c) CHECK(s.patches[0].mean[c] == Approx(2 * 100 * (c + 1)).margin(1e-3));
}

TEST_CASE("a saturated or misplaced light trap is coded", "[chart][light_trap]") {
  RawImage img = scene({10, 10, 10}, 0);
  const std::array<double, 8> outside = {120, 30, 170, 30, 170, 70, 120, 70};
  test::require_code([&] { measure_light_trap(img, outside); }, ErrorCode::CornersOutside);
  for (int y = 30; y < 70; ++y)
    for (int x = 120; x < 150; ++x) img.saturated[size_t(y) * img.width + x] = 7;
  test::require_code([&] { measure_light_trap(img, kTrap); }, ErrorCode::NoUsableData);
}

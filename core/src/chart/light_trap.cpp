// In-scene light trap (Abed 2013 App. C step 1): a one-patch layout sampled with the dark frame only.
#include "tristim/chart/light_trap.hpp"

#include <algorithm>

#include "tristim/error.hpp"

namespace tristim {

LightTrap measure_light_trap(const RawImage& image, const std::array<double, 8>& corners, const SampleOptions& options,
                             const FrameCalibration* calibration) {
  LayoutOptions one;
  one.chart = "custom";
  one.rows = 1;
  one.columns = 1;
  FrameCalibration dark_only;
  if (calibration) {
    dark_only.dark = calibration->dark;
    dark_only.dark_mode = calibration->dark_mode;
  }
  SampleOptions whole = options;  // the trap lies wholly inside the image, cut chart or not
  whole.partial = false;
  ChartSample s;
  try {
    s = sample_chart(image, one, corners, whole, calibration ? &dark_only : nullptr);
  } catch (const Error& e) {  // the message names the trap, not a chart
    if (e.code() != ErrorCode::CornersOutside) throw;
    throw Error(ErrorCode::CornersOutside, std::string("light trap: ") + e.what());
  }
  const PatchSample& p = s.patches.at(0);
  if (std::find(p.flags.begin(), p.flags.end(), "saturated") != p.flags.end())
    throw Error(ErrorCode::NoUsableData, "the light trap has saturated pixels: it is not dark, check its corners");
  LightTrap t;
  t.mean = p.mean;
  t.std = p.std;
  t.n = p.n;
  t.flags = p.flags;
  t.sample_quad = p.sample_quad;
  return t;
}

std::vector<OptionSpec> light_trap_option_table(int W, int H) {
  if (W < 1 || H < 1)
    throw Error(ErrorCode::InvalidArgument, "light trap: the image has no pixels (" + std::to_string(W) + " x " +
                                                std::to_string(H) + ")");
  auto px = [](const char* name, const char* label, double def, double lo, double hi, const char* what) {
    OptionSpec o = number_option(name, label, def, lo, hi, what, "integer");
    o.step = 1;
    o.unit = "px";
    return o;
  };
  // Abed et al. 2013 App. C step 1: the trap is marked like a patch, inside the photographed scene.
  return {px("x", "Light trap x", 0, 0, W - 1, "the box's left edge, pixels from the image's left"),
          px("y", "Light trap y", 0, 0, H - 1, "the box's top edge, pixels from the image's top"),
          px("width", "Light trap width", 1, 1, W, "the box's width; left + width at most the image's width"),
          px("height", "Light trap height", 1, 1, H, "the box's height; top + height at most the image's height")};
}

FrameCalibration with_light_trap(const FrameCalibration& calibration, const LightTrap& trap) {
  FrameCalibration c = calibration;
  c.flare = trap.mean;
  return c;
}

}  // namespace tristim

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
  const ChartSample s = sample_chart(image, one, corners, whole, calibration ? &dark_only : nullptr);
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

FrameCalibration with_light_trap(const FrameCalibration& calibration, const LightTrap& trap) {
  FrameCalibration c = calibration;
  c.flare = trap.mean;
  return c;
}

}  // namespace tristim

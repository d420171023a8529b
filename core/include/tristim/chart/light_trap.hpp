// tristim — an in-scene light trap for flare (Abed, Berns & Masaoka 2013, Phase II and App. C
// step 1): a black cavity placed in the scene and marked in the image like a patch. Its mean
// camera RGB is what the scene adds to a perfect black (dark current and optical flare); it is
// subtracted per channel from every pixel before the chart is sampled (FrameCalibration::flare).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/capture/calibration.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/methods.hpp"

namespace tristim {

struct LightTrap {
  std::array<double, 3> mean{};      ///< per-channel mean of the trap's sample area, DN (dark-subtracted)
  std::array<double, 3> std{};       ///< sample standard deviation over its pixels
  int n = 0;                         ///< pixels averaged
  std::vector<std::string> flags;    ///< as PatchSample (e.g. "saturated": the trap is not dark)
  std::array<double, 8> sample_quad{};  ///< the sampled area's corners in the image
};

/// Measures the light trap whose four corners (clockwise from top-left, image coordinates as
/// chart/layout.hpp) are given, sampling its central `options.area`, on the image with only the
/// dark frame of `calibration` applied (no flat field, fall-off or earlier flare: the flare is
/// an additive level in raw DN). Errors as sample_chart (CornersOutside — its message starting
/// "light trap: " —, CornersCrossed, PatchTooSmall, FrameMismatch); NoUsableData when the trap's
/// pixels are saturated.
LightTrap measure_light_trap(const RawImage& image, const std::array<double, 8>& corners,
                             const SampleOptions& options = {}, const FrameCalibration* calibration = nullptr);

/// The rows of a light trap marked as a box of image pixels (the page's boxes: left x, top y,
/// width, height; its corners x, y, x + width, y, x + width, y + height, x, y + height) for a
/// `image_width` × `image_height` image, one OptionSpec each (integer pixels, step 1): x in
/// [0, image_width − 1], y in [0, image_height − 1], width in [1, image_width], height in
/// [1, image_height]. A box inside its rows with x + width ≤ image_width and y + height ≤
/// image_height lies in the image; measure_light_trap refuses one past an edge (CornersOutside).
/// Error(InvalidArgument) for an image without pixels.
std::vector<OptionSpec> light_trap_option_table(int image_width, int image_height);

/// `calibration` with its flare set to the trap's mean (what sample_chart then subtracts).
FrameCalibration with_light_trap(const FrameCalibration& calibration, const LightTrap& trap);

}  // namespace tristim

// The decoded image as JS holds it (`RawImage`, owning wasm memory: call .delete()): the linear
// image and the dark/flat calibration set on it. Shared by the bind files that take an image.
#pragma once
#include "boundary.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/capture/raw.hpp"

namespace tristim::wasm {

struct RawHandle {
  RawImage image;
  FrameCalibration calibration;
};

template <>
struct Conv<const RawHandle*> {
  static const RawHandle* from(const val& v) {
    if (absent(v) || !v.instanceof(val::module_property("RawImage"))) refuse("expected a RawImage from decodeRaw");
    return v.as<RawHandle*>(emscripten::allow_raw_pointers());
  }
};

/// f(the image with its dark/flat applied), without a copy when there is no calibration.
template <class F>
auto with_calibrated(const RawHandle& h, F f) {
  const auto& c = h.calibration;
  return c.dark || c.flat || c.falloff ? f(apply_calibration(h.image, c)) : f(h.image);
}

}  // namespace tristim::wasm

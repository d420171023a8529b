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

/// A frame for a core function that reads frames as decoded (the absolute chain normalises them
/// itself, eq 7: a dark or flat set on the handle is not applied): the handle's image; null: none.
template <>
struct Conv<const RawImage*> {
  static const RawImage* from(const val& v) { return absent(v) ? nullptr : &Conv<const RawHandle*>::from(v)->image; }
  static val to(const RawImage* p) { return p ? val(RawHandle{*p, {}}) : val::null(); }
};
/// A frame the core made (the virtual camera's) as a new RawImage handle (call .delete()).
template <>
struct Conv<RawImage> {
  static val to(const RawImage& r) { return val(RawHandle{r, {}}); }
  static RawImage from(const val& v) { return Conv<const RawHandle*>::from(v)->image; }
};

/// f(the image with its calibration applied: dark, light-trap flare, flat, fall-off), without a
/// copy when there is none. A light trap alone counts (Abed 2013 App. C step 1): `tristim apply
/// --light-trap` subtracts it with no dark or flat frame either.
template <class F>
auto with_calibrated(const RawHandle& h, F f) {
  const auto& c = h.calibration;
  return c.dark || c.flat || c.falloff || c.flare ? f(apply_calibration(h.image, c)) : f(h.image);
}

}  // namespace tristim::wasm

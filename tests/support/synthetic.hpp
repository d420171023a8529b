// Synthetic inputs shared by the Catch2 suite and the benchmarks (native and wasm; no test
// framework, no files): random patch tables, blank frames, a fall-off centred on a frame.
#pragma once
#include <cmath>
#include <random>

#include "tristim/capture/calibration.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/characterisation/models.hpp"

namespace tristim::test {

/// n patches of camera RGB drawn uniformly from [lo, hi) per channel by mt19937(seed), row by row
/// (the same values in every build).
inline PatchMatrix random_patches(int n, unsigned seed, double lo, double hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  PatchMatrix m(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) m(i, c) = u(rng);
  return m;
}

/// A w × h frame of zeros with nothing saturated; its metadata gives the size and `saturation`
/// as every channel's clip level.
inline RawImage blank_raw(int w, int h, double saturation) {
  RawImage img;
  img.width = w;
  img.height = h;
  img.meta.width = w;
  img.meta.height = h;
  img.meta.saturation = {saturation, saturation, saturation};
  img.rgb.assign(static_cast<size_t>(w) * h * 3, 0.f);
  img.saturated.assign(static_cast<size_t>(w) * h, 0);
  return img;
}

/// The fall-off `f` moved to a width × height frame: centred, r_scale the half-diagonal (f(r) is
/// in relative radius, so its coefficients stay).
inline FalloffFit centred_falloff(FalloffFit f, int width, int height) {
  f.width = width;
  f.height = height;
  f.centre_x = width / 2.0;
  f.centre_y = height / 2.0;
  f.r_scale = std::hypot(f.centre_x, f.centre_y);
  return f;
}

}  // namespace tristim::test

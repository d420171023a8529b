// Frame calibration: dark averaging/subtraction, flat field (Abed 2013 App. C), fall-off (Guarnera eq 7).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include "synthetic.hpp"
#include "test_support.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/error.hpp"

using tristim::test::code_of;

using namespace tristim;

namespace {

RawImage synthetic(int w, int h, const std::string& model = "Synthetic") {
  RawImage img = test::blank_raw(w, h, 10000);
  img.meta.make = "tristim";
  img.meta.model = model;
  return img;
}


}  // namespace

TEST_CASE("dark frames: average of N, subtracted per pixel or per channel", "[calibration]") {
  const int W = 20, H = 10;
  RawImage signal = synthetic(W, H);
  std::vector<RawImage> darks(3, synthetic(W, H));
  std::mt19937 rng(1);
  std::normal_distribution<float> noise(0, 2);
  std::vector<float> pattern(signal.rgb.size());
  for (size_t i = 0; i < pattern.size(); ++i) {
    pattern[i] = 10.0f + static_cast<float>(i % 7);  // fixed-pattern dark signal
    signal.rgb[i] = 500.0f + pattern[i];
  }
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < pattern.size(); ++i) darks[k].rgb[i] = pattern[i] + (k == 0 ? 1.f : k == 1 ? -1.f : 0.f);
  const DarkFrame dark = average_dark_frames({&darks[0], &darks[1], &darks[2]});
  CHECK(dark.frames == 3);
  for (size_t i = 0; i < pattern.size(); ++i) REQUIRE(dark.rgb[i] == Approx(pattern[i]));
  FrameCalibration cal;
  cal.dark = dark;
  const RawImage per_pixel = apply_calibration(signal, cal);
  for (float v : per_pixel.rgb) REQUIRE(v == Approx(500.0f));
  cal.dark_mode = DarkMode::PerChannel;
  const RawImage per_channel = apply_calibration(signal, cal);
  double mean = 0;
  for (float v : per_channel.rgb) mean += v / per_channel.rgb.size();
  CHECK(mean == Approx(500.0).epsilon(1e-6));
  CHECK(dark.noise[0] > 0);
}

TEST_CASE("dark frame of another size or camera: FRAME_MISMATCH", "[calibration][bad]") {
  const RawImage a = synthetic(20, 10), b = synthetic(22, 10), c = synthetic(20, 10, "Other");
  CHECK(code_of([&] { average_dark_frames({&a, &b}); }) == ErrorCode::FrameMismatch);
  CHECK(code_of([&] { average_dark_frames({&a, &c}); }) == ErrorCode::FrameMismatch);
  FrameCalibration cal;
  cal.dark = average_dark_frames({&b});
  CHECK(code_of([&] { apply_calibration(a, cal); }) == ErrorCode::FrameMismatch);
  cal.dark = average_dark_frames({&c});
  CHECK(code_of([&] { apply_calibration(a, cal); }) == ErrorCode::FrameMismatch);
  CHECK(code_of([&] { make_flat_field(b, &*cal.dark); }) == ErrorCode::FrameMismatch);
  CHECK(code_of([&] { average_dark_frames({}); }) == ErrorCode::InvalidArgument);
}

TEST_CASE("flat field: planted vignetting is removed per pixel (Abed App. C step 2)", "[calibration]") {
  const int W = 30, H = 20;
  RawImage target = synthetic(W, H), flat = synthetic(W, H);
  const float refl[3] = {0.2f, 0.4f, 0.6f};
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float vig = 1.0f - 0.3f * ((x - 15.f) * (x - 15.f) + (y - 10.f) * (y - 10.f)) / 325.f;
      for (int c = 0; c < 3; ++c) {
        const size_t i = (size_t(y) * W + x) * 3 + c;
        flat.rgb[i] = 8000.f * vig * (1.0f + 0.1f * c);
        target.rgb[i] = 8000.f * vig * (1.0f + 0.1f * c) * refl[c];
      }
    }
  FrameCalibration cal;
  cal.flat = make_flat_field(flat);
  const RawImage flattened = apply_calibration(target, cal);
  // Without a white reflectance the result is uniform (the vignetting is gone), in DN.
  for (int c = 0; c < 3; ++c) {
    const float first = flattened.rgb[c];
    for (size_t i = c; i < flattened.rgb.size(); i += 3) REQUIRE(flattened.rgb[i] == Approx(first).epsilon(1e-5));
  }
  // With the white's reflectance 0.9: values become reflectance factors, R_w * RGB / RGB_fl.
  cal.flat = make_flat_field(flat, nullptr, DarkMode::PerPixel, std::array<double, 3>{0.9, 0.9, 0.9});
  CHECK(cal.flat->reflectance_units);
  const RawImage refl_img = apply_calibration(target, cal);
  for (size_t i = 0; i < refl_img.rgb.size(); ++i) REQUIRE(refl_img.rgb[i] == Approx(0.9 * refl[i % 3]).epsilon(1e-5));
}

TEST_CASE("flat field with zeros: FLAT_FIELD_ZERO — bad reflectance: INVALID_ARGUMENT", "[calibration][bad]") {
  RawImage flat = synthetic(10, 10);
  for (auto& v : flat.rgb) v = 1000.f;
  flat.rgb[3 * 55 + 1] = 0.f;
  CHECK(code_of([&] { make_flat_field(flat); }) == ErrorCode::FlatFieldZero);
  flat.rgb[3 * 57 + 2] = std::nanf("");  // a later element too: the first one is named
  try {
    make_flat_field(flat);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("pixel (5, 5) channel G") != std::string::npos);
  }
  flat.rgb[3 * 57 + 2] = 1000.f;
  RawImage black = synthetic(10, 10);
  CHECK(code_of([&] { fit_falloff_Guarnera2018(black); }) == ErrorCode::FlatFieldZero);
  flat.rgb[3 * 55 + 1] = 1000.f;
  CHECK(code_of([&] { make_flat_field(flat, nullptr, DarkMode::PerPixel, std::array<double, 3>{0, 1, 1}); }) ==
        ErrorCode::InvalidArgument);
  // A dark frame brighter than the flat leaves no signal.
  RawImage bright_dark = synthetic(10, 10);
  for (auto& v : bright_dark.rgb) v = 2000.f;
  const DarkFrame d = average_dark_frames({&bright_dark});
  CHECK(code_of([&] { make_flat_field(flat, &d); }) == ErrorCode::FlatFieldZero);
}

TEST_CASE("radial fall-off: planted f(r) = 1 + 0.2 r + 0.4 r^2 is recovered (Guarnera eq 7)", "[calibration]") {
  const int W = 300, H = 200;
  RawImage flat = synthetic(W, H);
  const double cx = W / 2.0, cy = H / 2.0, rs = std::hypot(cx, cy);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy) / rs;
      const double f = 1 + 0.2 * r + 0.4 * r * r;
      for (int c = 0; c < 3; ++c) flat.rgb[(size_t(y) * W + x) * 3 + c] = static_cast<float>(5000.0 * (1 + c) / f);
    }
  const FalloffFit fit = fit_falloff_Guarnera2018(flat);
  CHECK(fit.p3 == 1.0);
  CHECK(fit.p1 == Approx(0.4).margin(2e-3));
  CHECK(fit.p2 == Approx(0.2).margin(2e-3));
  CHECK(fit.rms_residual < 1e-3);
  CHECK(fit.max_residual < 5e-3);
  CHECK(fit.factor(cx, cy) == Approx(1.0));
  FrameCalibration cal;
  cal.falloff = fit;
  const RawImage corrected = apply_calibration(flat, cal);
  for (size_t i = 0; i < corrected.rgb.size(); i += 3) REQUIRE(corrected.rgb[i] == Approx(5000.0).epsilon(3e-3));
}

TEST_CASE("saturation mask survives calibration", "[calibration]") {
  RawImage img = synthetic(4, 4);
  for (auto& v : img.rgb) v = 100.f;
  img.saturated[5] = 3;
  RawImage flat = synthetic(4, 4);
  for (auto& v : flat.rgb) v = 50.f;
  FrameCalibration cal;
  cal.flat = make_flat_field(flat);
  const RawImage out = apply_calibration(img, cal);
  CHECK(out.saturated[5] == 3);
  CHECK(out.saturated[4] == 0);
}

TEST_CASE("apply_calibration equals FrameCalibration::calibrated pixel by pixel, bit for bit", "[calibration]") {
  // The whole-image kernel (row passes that vectorise) must give exactly what sampling computes
  // per pixel, for every combination of dark mode, flare, flat and fall-off.
  const int W = 37, H = 23;  // odd sizes: no row is a multiple of a vector width
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 4000.f), d(0.f, 40.f), fl(800.f, 1200.f);
  RawImage img = synthetic(W, H), dark = synthetic(W, H), flat = synthetic(W, H);
  for (auto& v : img.rgb) v = u(rng);
  for (auto& v : dark.rgb) v = d(rng);
  for (auto& v : flat.rgb) v = fl(rng);
  // Values where an absent step done as "x - 0" or "x * 1" would show if it were not exact.
  img.rgb[4] = -0.0f;
  img.rgb[5] = 1e-40f;  // subnormal
  img.rgb[3 * W + 7] = -3e-39f;
  const DarkFrame avg = average_dark_frames({&dark});
  const FlatField ff = make_flat_field(flat, &avg);
  FalloffFit fo;
  fo.p1 = 0.31;
  fo.p2 = -0.07;
  fo = test::centred_falloff(fo, W, H);
  for (int mask = 0; mask < 32; ++mask) {
    FrameCalibration cal;
    if (mask & 1) cal.dark = avg;
    cal.dark_mode = (mask & 2) ? DarkMode::PerChannel : DarkMode::PerPixel;
    if (mask & 4) cal.flare = std::array<double, 3>{1.25, 0.7, 3.1};
    if (mask & 8) cal.flat = ff;
    if (mask & 16) cal.falloff = fo;
    const RawImage out = apply_calibration(img, cal);
    REQUIRE(out.rgb.size() == img.rgb.size());
    size_t mismatches = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        float ref[3];
        cal.calibrated(img, x, y, ref);
        for (int c = 0; c < 3; ++c) {
          const float got = out.rgb[(size_t(y) * W + x) * 3 + c];
          std::uint32_t got_bits, ref_bits;  // bit for bit: -0 and +0 differ
          std::memcpy(&got_bits, &got, 4);
          std::memcpy(&ref_bits, &ref[c], 4);
          if (got_bits != ref_bits && mismatches++ == 0)
            FAIL_CHECK("mask " << mask << " pixel (" << x << ", " << y << ") channel " << c << ": " << got
                               << " != " << ref[c] << " (tolerance 0)");
        }
      }
    CHECK(mismatches == 0);
  }
}

// Declarations: image decoding — camera RAW, and 8/16-bit TIFF, 8/16-bit PNG and JPEG with their
// values as stored (capture/image.hpp: decode_any picks the decoder from the file's first bytes)
// — into the RawImage handle, which owns wasm memory: call .delete(); frame
// calibration set on an image, chart sampling and applying a profile to a decoded RAW.
//
// RawImage methods: width(), height() (the measurement image: half resolution for Bayer),
// metadata() -> RawMetadata (by its field list: the object `tristim inspect` prints, without
// linear_hash), linearHash(), preview(maxSide) -> Preview (display only),
// setDark(frames: RawImage | RawImage[], mode 'per_pixel' | 'per_channel' (default per_pixel; the
// recipe's capture.dark_mode; 'pixel' | 'channel' accepted as aliases)) -> DarkFrame summary,
// clearDark(), setFlat(flat, mode 'pixel' | 'radial', white_reflectance?: number | [r, g, b])
// -> FlatField summary or FalloffFit (by its field list), clearFlat(), saturationMask() -> Uint8Array(w·h),
// linearRGB() -> Float32Array(3·w·h) with the dark/flat set on this image applied,
// setLightTrap(corners[8], SampleOptions?) -> LightTrap (Abed 2013 App. C step 1: the trap's mean
// after the dark frame becomes the flare subtracted from every pixel), clearLightTrap().
#include "tristim/capture/image.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/profile/export.hpp"
#include "raw_handle.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using emscripten::value_object;
using wasm::Conv;
using wasm::def;
using wasm::guard;
using wasm::RawHandle;
using wasm::with_calibrated;

namespace {

val set_dark(RawHandle& h, val frames, val mode) {
  return guard([&] {
    h.calibration = with_dark_frames(h.calibration, h.image,
                                     frames.isArray() ? Conv<std::vector<const RawImage*>>::from(frames)
                                                      : std::vector<const RawImage*>{&Conv<const RawHandle*>::from(frames)->image},
                                     Conv<std::string>::from(mode));
    return val(*h.calibration.dark);
  });
}

/// reflectance: none, a number (grey) or [R, G, B].
val set_flat(RawHandle& h, val flat, val mode, val reflectance) {
  return guard([&] {
    const std::string m = Conv<std::string>::from(mode);
    h.calibration = with_flat_frame(h.calibration, h.image, Conv<const RawHandle*>::from(flat)->image, m,
                                    reflectance.isNumber() ? std::vector<double>{reflectance.as<double>()}
                                                           : Conv<std::vector<double>>::from(reflectance));
    return m == "radial" ? Conv<FalloffFit>::to(*h.calibration.falloff) : val(*h.calibration.flat);
  });
}

/// Measures the light trap on the image with its dark frame (an earlier flare is not subtracted)
/// and makes its mean the flare of the image's calibration.
val set_light_trap(RawHandle& h, val corners, val options) {
  return guard([&] {
    FrameCalibration base = h.calibration;
    base.flare.reset();
    const LightTrap trap = measure_light_trap(h.image, Conv<std::array<double, 8>>::from(corners),
                                              Conv<SampleOptions>::from(options), &base);
    h.calibration = with_light_trap(base, trap);
    return val(trap);
  });
}

RawHandle decode(val bytes) {
  return guard([&] { return RawHandle{decode_any(wasm::vector_from<uint8_t>(bytes)), {}}; });
}

ChartSample sample(const RawHandle* h, const LayoutOptions& layout, const std::array<double, 8>& corners,
                   const SampleOptions& options) {
  return sample_chart(h->image, layout, corners, options, &h->calibration);
}

/// The profile applied to the image's linear camera RGB (dark/flat applied) -> XYZ image.
Image3f apply_to_raw(const Profile& profile, const RawHandle* h) {
  return with_calibrated(*h, [&](const RawImage& img) { return apply_profile(profile, img.rgb.data(), img.width, img.height); });
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_raw) {
  using emscripten::class_;
  using emscripten::optional_override;
  { using S = Preview; value_object<S>("Preview") FIELD(width) FIELD(height) FIELD(scale) FIELD(rgba); }
  { using S = DarkFrame; value_object<S>("DarkFrame") FIELD(width) FIELD(height) FIELD(frames) FIELD(make) FIELD(model)
      FIELD(mean) FIELD(noise); }
  { using S = FlatField; value_object<S>("FlatField") FIELD(width) FIELD(height) FIELD(make) FIELD(model)
      FIELD(reflectance_units) FIELD(target); }
  { using S = SampleOptions; value_object<S>("SampleOptions") FIELD(area) FIELD(min_pixels) FIELD(dark_fraction)
      FIELD(nonuniform_threshold) FIELD(partial); }
  { using S = PatchSample; value_object<S>("PatchSample") FIELD(id) FIELD(mean) FIELD(std) FIELD(n)
      FIELD(saturated_fraction) FIELD(flags) FIELD(centre) FIELD(quad) FIELD(sample_quad); }
  { using S = LightTrap; value_object<S>("LightTrap") FIELD(mean) FIELD(std) FIELD(n) FIELD(flags) FIELD(sample_quad); }
  { using S = ChartSample; value_object<S>("ChartSample") FIELD(layout) FIELD(homography) FIELD(patches) FIELD(missing); }
  { using S = Image3f; value_object<S>("Image3f") FIELD(width) FIELD(height) FIELD(pixels); }

  class_<RawHandle>("RawImage")
      .function("width", optional_override([](const RawHandle& h) { return h.image.width; }))
      .function("height", optional_override([](const RawHandle& h) { return h.image.height; }))
      .function("metadata", optional_override([](const RawHandle& h) { return Conv<RawMetadata>::to(h.image.meta); }))
      .function("linearHash", optional_override([](const RawHandle& h) { return hash_hex(linear_data_hash(h.image)); }))
      .function("preview", optional_override([](const RawHandle& h, int side) {
                  return guard([&] { return val(render_preview(h.image, side)); }); }))
      .function("setDark", optional_override([](RawHandle& h, val f) { return set_dark(h, f, val::undefined()); }))
      .function("setDark", &set_dark)
      .function("clearDark", optional_override([](RawHandle& h) { h.calibration.dark.reset(); }))
      .function("setFlat", optional_override([](RawHandle& h, val f) { return set_flat(h, f, val::undefined(), val::undefined()); }))
      .function("setFlat", optional_override([](RawHandle& h, val f, val m) { return set_flat(h, f, m, val::undefined()); }))
      .function("setFlat", &set_flat)
      .function("clearFlat", optional_override([](RawHandle& h) { h.calibration.flat.reset(); h.calibration.falloff.reset(); }))
      .function("setLightTrap", optional_override([](RawHandle& h, val c) { return set_light_trap(h, c, val::undefined()); }))
      .function("setLightTrap", &set_light_trap)
      .function("clearLightTrap", optional_override([](RawHandle& h) { h.calibration.flare.reset(); }))
      .function("saturationMask", optional_override([](const RawHandle& h) { return Conv<std::vector<uint8_t>>::to(h.image.saturated); }))
      .function("linearRGB", optional_override([](const RawHandle& h) {
                  return guard([&] { return with_calibrated(h, [](const RawImage& i) { return Conv<std::vector<float>>::to(i.rgb); }); }); }));
  emscripten::function("decodeRaw", &decode);
  def<&sample>("sampleChart");
  def<&apply_to_raw>("applyProfile");
  def<&apply_profile_to_pixels>("applyProfileToImage");
}

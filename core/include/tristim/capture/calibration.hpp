// tristim — frame calibration of linear RAW images: dark frames, flat field, radial fall-off.
//
// Order applied to each measurement pixel (x, y), channel c (values in black-subtracted DN):
//   v = (raw(x,y,c) - dark(x,y,c) - flare_c) * flat_gain(x,y,c) * f(r(x,y))
// dark: Abed et al. 2013, App. C step 1 (light trap / lens cap, average of N frames);
// flare_c: App. C step 1 with the light trap in the scene (chart/light_trap.hpp): the per-channel
//   mean of the trap, measured on the dark-subtracted image, removes this scene's optical flare;
// flat_gain: App. C step 2 (multiply by R_w / RGB_fl per pixel);
// f(r): Guarnera et al. 2018, eq (7) (radial fall-off, f = p1 r² + p2 r + p3, f(centre) = 1).
// The per-pixel flat already contains the lens fall-off, so use either a flat or a fall-off fit,
// not both (apply_calibration allows both and multiplies them; that is the caller's choice).
// Saturation is never recomputed: RawImage::saturated (from the raw values) stays authoritative.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tristim/capture/raw.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/methods.hpp"

namespace tristim {

enum class DarkMode {
  PerPixel,    ///< subtract the averaged dark frame pixel by pixel
  PerChannel,  ///< subtract one mean value per channel (robust for few, noisy dark frames)
};

/// The mode's one spelling, "per_pixel" | "per_channel": what the CLI's --dark-mode, the recipe's
/// capture.dark_mode, the page and the wasm binding's setDark all write and document.
const char* dark_mode_id(DarkMode mode);
/// The mode an id names: "per_pixel" | "per_channel", or the aliases "pixel" | "channel" (the
/// spelling `sample --dark-mode` and setDark took before there was one spelling; accepted on input
/// so existing command lines, scripts and recipes keep working, never written).
/// Error(InvalidArgument) naming the canonical ids otherwise.
DarkMode dark_mode_from_id(std::string_view id);

/// The two ways a flat-field frame corrects a capture, as a method table (the page's picker; the
/// recipe records the choice as capture.flat_field or capture.falloff): "pixel" (make_flat_field,
/// App. C step 2) and "radial" (fit_falloff_Guarnera2018, eq (7)). Neither has options.
const std::vector<MethodInfo>& flat_field_methods();

/// Average of N dark frames (same camera, same size), black-subtracted DN.
struct DarkFrame {
  int width = 0, height = 0, frames = 0;
  std::string make, model;
  std::vector<float> rgb;               ///< width*height*3 averaged values
  std::array<double, 3> mean{};         ///< per-channel mean of `rgb`
  std::array<double, 3> noise{};        ///< per-channel std of one frame's pixels around the
                                        ///< average (the noise floor n of Guarnera eq (7))
};

/// Averages the frames. FrameMismatch when sizes, make or model differ; InvalidArgument if none.
DarkFrame average_dark_frames(const std::vector<const RawImage*>& frames);

/// Per-pixel flat-field gains (Abed App. C step 2).
struct FlatField {
  int width = 0, height = 0;
  std::string make, model;
  /// width*height*3 multipliers: target_c / (flat(x,y,c) - dark(x,y,c)), where target_c is the
  /// white's reflectance R_w,c when given (values become reflectance factors relative to the
  /// flat's white, dimensionless), otherwise the flat's own channel mean (values stay in DN).
  std::vector<float> gain;
  bool reflectance_units = false;
  std::array<double, 3> target{};
};

/// Builds gains from a flat-field image (dark-subtracted with `dark` when given).
/// FlatFieldZero if any pixel of the (dark-subtracted) flat is <= 0 in any channel;
/// FrameMismatch if flat and dark differ in size or camera; InvalidArgument for reflectances
/// outside (0, 1.5].
FlatField make_flat_field(const RawImage& flat, const DarkFrame* dark = nullptr,
                          DarkMode dark_mode = DarkMode::PerPixel,
                          const std::optional<std::array<double, 3>>& white_reflectance = std::nullopt);

/// Radial fall-off correction f(r) = p1·r² + p2·r + p3 with p3 = f(centre) = 1 (Guarnera eq (7)).
/// r is the distance of a pixel centre from the image centre divided by the half-diagonal, so
/// r ∈ [0, 1] and the coefficients do not depend on resolution.
struct FalloffFit {
  double p1 = 0, p2 = 0, p3 = 1;
  double centre_x = 0, centre_y = 0;  ///< image centre (width/2, height/2)
  double r_scale = 1;                 ///< half-diagonal in pixels
  int width = 0, height = 0;
  int bins = 0;                       ///< radial bins used in the fit
  double rms_residual = 0;            ///< RMS over bins of f(r)·L(r)/L(0) - 1 (0 = flat after correction)
  double max_residual = 0;            ///< largest |f(r)·L(r)/L(0) - 1| over bins
  double factor(double x, double y) const;  ///< f at image point (x, y)
};

/// Fits the fall-off from a uniformly lit flat-field image: radial profile L(r) of the
/// per-channel-normalised mean of R, G, B in 64 bins (saturated pixels skipped), then
/// 1/L(r) = (1 + p2 r + p1 r²)/L(0) fitted by linear least squares (relative errors), so
/// f(r) = L(0)/L(r) has p3 = f(centre) = 1 exactly.
/// FlatFieldZero if the flat has no positive signal; InvalidArgument if fewer than 3 bins.
FalloffFit fit_falloff_Guarnera2018(const RawImage& flat, const DarkFrame* dark = nullptr);

/// Everything applied to an image before sampling. All parts optional.
struct FrameCalibration {
  std::optional<DarkFrame> dark;
  DarkMode dark_mode = DarkMode::PerPixel;
  std::optional<FlatField> flat;
  std::optional<FalloffFit> falloff;
  /// Per-channel level subtracted from every pixel after the dark frame: the mean of an in-scene
  /// light trap (Abed 2013 App. C step 1; measure_light_trap in chart/light_trap.hpp), DN.
  std::optional<std::array<double, 3>> flare;

  /// FrameMismatch if a frame's size or camera (make, model) differs from the image's.
  void check_compatible(const RawImage& image) const;
  /// Dark-subtracted value (DN) of pixel (x, y): used for the noise-floor ("dark") test.
  void dark_subtracted(const RawImage& image, int x, int y, float out[3]) const;
  /// Fully calibrated value of pixel (x, y) (dark, flare, flat gain, fall-off).
  void calibrated(const RawImage& image, int x, int y, float out[3]) const;
  /// Noise floor per channel (std of the dark frame), 0 without a dark frame.
  std::array<double, 3> noise_floor() const;
};

/// `base` with the dark frame averaged from `frames`, subtracted in `mode` (dark_mode_from_id's
/// ids or aliases; "": per_pixel). FrameMismatch if it does not fit `image`.
FrameCalibration with_dark_frames(FrameCalibration base, const RawImage& image,
                                  const std::vector<const RawImage*>& frames, std::string_view mode);
/// `base` with the flat frame as `mode` uses it (flat_field_methods(): "pixel" or "" a per-pixel
/// flat field with `white_reflectance` of 0 values (none), 1 (grey) or 3 (R, G, B); "radial" the
/// fall-off fit), after `base`'s dark frame; the other flat correction is cleared. FrameMismatch
/// if it does not fit `image`; InvalidArgument for another mode or reflectance count.
FrameCalibration with_flat_frame(FrameCalibration base, const RawImage& image, const RawImage& flat, std::string_view mode,
                                 const std::vector<double>& white_reflectance = {});

/// A calibrated copy of the image (same size, same saturation mask and metadata).
RawImage apply_calibration(const RawImage& image, const FrameCalibration& calibration);

}  // namespace tristim

// The fall-off fit's field list (defined in calibration.cpp): the absolute profile's JSON and the
// wasm binding (setFlat(…, 'radial')) use it.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(FalloffFit);
}  // namespace tristim::fields

// The absolute tele-colorimeter (Guarnera, Bianco & Schettini 2018, section 3.1), part 1:
// exposure settings, the per-pixel normalisation of eq (7), the saturation level measured from
// the data, the channel areas and the reliability zones Z_u, Z_c, Z_o.
//
// Units: raw values are the decoder's black-subtracted DN (RawImage::rgb). The noise floor n is
// the mean level of averaged lens-cap frames in the same units (what is left after the black
// level: pedestal, dark current), per channel; the paper assumes it channel-independent, a
// single value is the special case of three equal ones. S is the clip level in the same units.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tristim/capture/calibration.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

/// Exposure of one shot. ε = t/N² is what the sensor integrates (eq 5); the ISO enters as a
/// gain relative to the training ISO, so ε = t/N²·ISO/ISO_ref.
struct ExposureSettings {
  double exposure_s = 0;  ///< t, seconds
  double f_number = 0;    ///< N
  double iso = 0;         ///< ISO speed (0: unknown, no ISO scaling)
  /// ε = t/N²·(ISO/iso_reference); the ISO factor is 1 when either ISO is 0.
  double factor(double iso_reference = 0) const;
  /// "1/60 s f/8 ISO 100".
  std::string label() const;
};

/// Exposure time, f-number and ISO of a RAW file. Error(MissingMetadata) naming `source` and
/// each missing field (0 in the metadata) when the exposure time or the f-number is missing;
/// a missing ISO is allowed (no ISO scaling) unless `require_iso`.
ExposureSettings exposure_from_metadata(const RawMetadata& meta, const std::string& source,
                                        bool require_iso = false);

/// Channel areas A_R, A_G, A_B of eq (7): trapezoidal integrals of the R, G, B sensitivity
/// curves over wavelength (nm × relative units). Only their ratios matter.
/// Error(InvalidArgument) unless ssf has 3 columns with a positive area each.
std::array<double, 3> channel_areas(const SpectralData& ssf);

/// The clip level S per channel and how it was found.
struct SaturationEstimate {
  std::array<double, 3> level{};     ///< S used (DN, black-subtracted)
  std::array<double, 3> reported{};  ///< LibRaw's (RawMetadata::saturation)
  /// level / reported: the saturation fraction (1 when LibRaw's maximum is right; < 1 when the
  /// body clips lower than LibRaw says).
  std::array<double, 3> fraction{};
  std::array<bool, 3> measured{};        ///< true: a pile-up of clipped values was found
  std::array<double, 3> clipped_pixels{};  ///< fraction of all pixels (all frames) at the level
};

/// Measures the clip level per channel from frames that hold clipped pixels (e.g. the
/// brightest training shots): the largest value of the channel is the clip level when a
/// pile-up sits there — at least 16 pixels within δ = max(1 DN, 0.1 % of the value) of the
/// maximum, and more than 4× the density just below (the 4δ band under it) — which unclipped
/// noisy data never show. Without a pile-up the channel keeps LibRaw's level (measured =
/// false). A measured level above LibRaw's is capped at LibRaw's. Error(InvalidArgument) if no
/// frames; FrameMismatch if they differ in camera.
SaturationEstimate measure_saturation(const std::vector<const RawImage*>& frames);

/// Reliability zones of one value, section 3.1: with u = (v − n)/(S − n) in [0, 1],
/// Z_u: u < 1/w, Z_c: 1/w ≤ u ≤ (w − 1)/w, Z_o: u > (w − 1)/w; Saturated: at or above the clip.
enum class Zone : std::uint8_t { Under, Centre, Over, Saturated };
const char* zone_name(Zone zone);  ///< "Z_u", "Z_c", "Z_o", "saturated"

/// Everything eq (7) needs, per channel, plus the zone parameter w.
struct Normalisation {
  std::array<double, 3> noise_floor{};               ///< n, DN
  /// σ of one lens-cap frame around the average (DarkFrame::noise), DN: a value is detectable
  /// only above n + 5σ (0 without lens-cap frames: any value above n).
  std::array<double, 3> noise_sigma{};
  std::array<double, 3> saturation{};                ///< S, DN
  std::array<double, 3> areas{{1.0, 1.0, 1.0}};      ///< A_R, A_G, A_B (1, 1, 1: no area term)
  std::optional<FalloffFit> falloff;                 ///< f(r); none: f = 1
  double w = 10;  ///< zone parameter (> 2): Z_c = [1/w, (w−1)/w] of the (S − n) interval

  /// u = (v − n)/(S − n): where v sits in the usable interval (0 at the floor, 1 at the clip).
  double unit(int c, double v) const { return (v - noise_floor[c]) / (saturation[c] - noise_floor[c]); }
  /// A_G/A_c (1 for G).
  double area_ratio(int c) const { return areas[1] / areas[c]; }
  /// Eq (7) at measurement pixel (x, y): (v − n)·A_G/((S − n)·A_c)·f(r).
  double normalised(int c, double v, int x, int y) const;
  /// f(r) at measurement pixel (x, y) (1 without a fall-off fit).
  double falloff_factor(int x, int y) const;
  /// Zone of a value; `flagged` = the decoder marked the pixel saturated in this channel.
  /// Saturated when flagged or v ≥ S − max(0.5 DN, 1e-4·(S − n)).
  Zone zone(int c, double v, bool flagged = false) const;
  /// The detection threshold in units of u: 5σ/(S − n).
  double detection_unit(int c) const { return 5 * noise_sigma[c] / (saturation[c] - noise_floor[c]); }
  /// Error(InvalidArgument) unless S > n, areas > 0 and w > 2 (and finite).
  void check() const;
};

/// A Normalisation from its parts: n and σ from averaged lens-cap frames (their per-channel
/// mean and DarkFrame::noise; zeros without frames), S from `saturation`, areas from the sensitivities (none: 1, 1, 1).
Normalisation make_normalisation(const DarkFrame* lens_cap, const SaturationEstimate& saturation,
                                 const SpectralData* ssf = nullptr,
                                 const std::optional<FalloffFit>& falloff = std::nullopt, double w = 10);

}  // namespace tristim

// The absolute tele-colorimeter (Guarnera 2018 section 3.1), part 2: training stimuli and the
// inverse OECF per channel (eq 8) fitted across every {t, N} at once, with the reciprocity check.
//
// One curve for every exposure: F⁻¹ maps R' (eq 7) to the exposure H = Y·ε, ε = t/N²·ISO/ISO_ref
// (normalisation.hpp), so L = F⁻¹(R')/ε in cd/m² (eq 10). This holds when the reciprocity law
// holds (the paper's assumption: "all parallel if the reciprocity law is verified"). The check
// fits each exposure on its own and compares it with the common curve:
//   scale_ratio_e = effective / nominal ε_e: the factor s minimising Σ_i ((F⁻¹(R'_i)/(ε_e·s) −
//                   Y_i)/(Y_i + floor))² over that exposure's stimuli (1 under reciprocity);
//   slope_difference_e = k3 of the exposure's own fit − k3 of the common curve (0 when the
//                   per-exposure curves are parallel on log axes).
// The report lists every exposure; reciprocity_ok is false (and `message` says which exposure
// and channel) when |scale_ratio − 1| > reciprocity_tolerance or |slope_difference| >
// slope_tolerance. Nothing is hidden or corrected: the common curve is still returned.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/absolute/normalisation.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/linearisation/guarnera2018.hpp"

namespace tristim {

/// One training stimulus photographed in one shot (a region of a frame, or given per patch).
struct TrainingStimulus {
  std::string id;
  ExposureSettings exposure;
  /// Black-subtracted DN of the region: Σ v·f / Σ f over its pixels (fall-off-weighted mean,
  /// so that (raw − n)·falloff is the region mean of (v − n)·f exactly).
  Vec3 raw_RGB = Vec3::Zero();
  double falloff = 1;              ///< mean f(r) over the region (1: at the centre, or none)
  std::array<bool, 3> saturated{}; ///< any pixel of the region in the saturated zone
  Vec3 XYZ = Vec3::Zero();         ///< measured tristimulus values, cd/m²
  /// true: an equal-tristimulus stimulus (X = Y = Z) for the inverse OECF (section 3.1);
  /// false: a chromatic stimulus for the colour matrix (section 3.2).
  bool luminance_set = true;
};

/// The region [x, x+w) × [y, y+h) of a frame as a training stimulus. Error(InvalidArgument)
/// for a region outside the frame or empty.
TrainingStimulus sample_stimulus(const RawImage& frame, int x, int y, int w, int h,
                                 const Normalisation& normalisation, const ExposureSettings& exposure,
                                 const Vec3& XYZ, const std::string& id, bool luminance_set = true);

/// Eq (7) of a stimulus, channel c.
double stimulus_normalised(const TrainingStimulus& s, const Normalisation& n, int c);

struct LuminanceFitOptions {
  OecfFitOptions oecf;
  double iso_reference = 0;            ///< 0: the ISO of the first stimulus (0 if unknown)
  double reciprocity_tolerance = 0.02; ///< |scale_ratio − 1| above this fails the check
  double slope_tolerance = 0.03;       ///< |k3_e − k3| above this fails the check
  /// Relative tolerance of the monotonicity check: within one exposure and channel, R' of a
  /// brighter stimulus may fall below a dimmer one's by at most this fraction of the channel's
  /// range plus 3 noise-floor-free DN (noise); more is Error(NonMonotonic).
  double monotonic_tolerance = 0.01;
};

/// The reciprocity report of one {t, N, ISO}.
struct ExposureReport {
  ExposureSettings exposure;
  double factor = 0;                     ///< ε relative to iso_reference
  std::array<int, 3> samples{};          ///< usable (unsaturated) stimuli per channel
  std::array<bool, 3> own_fit{};         ///< the exposure had ≥ 3 usable stimuli with Y > 0
  std::array<InverseOecf, 3> own;        ///< the exposure's own eq (8) fit, in exposure units
  std::array<double, 3> scale_ratio{{1.0, 1.0, 1.0}};
  std::array<double, 3> slope_difference{};
  std::array<double, 3> rms_relative{};  ///< common curve on this exposure's stimuli
  bool parallel = true;                  ///< within both tolerances in every channel
};

struct LuminanceFit {
  std::array<InverseOecf, 3> curves;     ///< the common eq (8) curve per channel (H = Y·ε)
  std::array<OecfFit, 3> fits;           ///< fit summaries
  double iso_reference = 0;
  std::vector<ExposureReport> exposures; ///< sorted by ε, shortest first
  bool reciprocity_ok = true;
  std::string message;                   ///< which exposures fail, empty when none
  /// L(c) = F⁻¹(R')/ε in cd/m² (eq 10) for a normalised value R' shot at `exposure`.
  double luminance(int c, double normalised, const ExposureSettings& exposure) const;
};

/// Fits eq (8) per channel to the luminance-set stimuli (X = Y = Z, luminance Y), every exposure
/// at once with ε scaling, and reports reciprocity per exposure. Saturated channels of a
/// stimulus are left out. Errors: NoUsableData (no stimulus with an unsaturated channel),
/// NonMonotonic (a brighter stimulus reads lower beyond noise, naming both), NegativeValue
/// (Y < 0), MissingMetadata (an exposure without t or N), TooFewPatches (< 3 per channel).
LuminanceFit fit_luminance_Guarnera2018(const std::vector<TrainingStimulus>& stimuli,
                                        const Normalisation& normalisation,
                                        const LuminanceFitOptions& options = {});

/// L(R), L(G), L(B) of a stimulus, cd/m² (eq 10).
Vec3 stimulus_luminance(const TrainingStimulus& s, const Normalisation& n, const LuminanceFit& fit);

}  // namespace tristim

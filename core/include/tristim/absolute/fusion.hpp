// The absolute tele-colorimeter (Guarnera 2018 section 3.1), part 3: per-pixel luminance per
// channel, L(R), L(G), L(B) in cd/m² (eq 10), from one or several exposures of a scene.
//
// Two ways to combine exposures, both per pixel and per channel:
//  * Recursive (the paper's Algorithm 1): start at the exposure {t_g, N_g}; a value in Z_c is
//    used; in Z_u the next longer exposure is tried, in Z_o (or saturated) the next shorter
//    one. The paper steps to 2·t_g or t_g/2; here "next" is the neighbouring exposure of the
//    bracket in ε = t/N², whatever its ratio. When the walk reverses (a value in Z_u whose longer
//    neighbour is in Z_o — the bracket steps are wider than Z_c), the Z_o value is used unless it
//    is saturated; at the end of the bracket the last value is used (saturated: none, NaN).
//  * Weighted (default): every exposure that is not saturated contributes, with the weight
//        w_e = max(h(u_e), 1e-6) · ε_e,
//    where u_e = (v − n)/(S − n) and h is the reliability of the zones: h = 0 for u ≤ u_min
//    (not detectable: below n + 5σ of the lens-cap frames), h = w·u in Z_u (rising to 1 at 1/w),
//    h = 1 in Z_c,
//    h = w·(1 − u) in Z_o (falling to 0 at the clip), and 0 when saturated. The factor ε_e
//    (= t/N²·ISO/ISO_ref) is the inverse variance of L_e = F⁻¹(R'_e)/ε_e under shot noise
//    (var L_e ∝ L/ε_e), so longer exposures count more while reliable. The 1e-6 floor keeps a
//    pixel that is dark in every exposure measured (mostly by the longest one) instead of
//    undefined. L = Σ w_e L_e / Σ w_e; NaN where every exposure is saturated.
// Frames are added one at a time (streaming: only the accumulators — 6 floats, a weight, a
// byte and a 16-bit mask per pixel — stay in memory, not every decoded frame).
// Which exposures served each pixel: `source` is the exposure with the largest Σ_c h·ε (the
// dominant one; for Algorithm 1 the one used for G), `contributors` the bit mask of every
// exposure with h > 0 in some channel (for Algorithm 1, the ones used in any channel).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tristim/absolute/luminance.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/capture/raw.hpp"

namespace tristim {

namespace detail {
struct FusionTables;  // fusion.cpp: the eq (8) root tables, shared by every frame of a bracket
}

enum class FusionMode { Weighted, Recursive };
const char* fusion_mode_id(FusionMode mode);   ///< "weighted" | "recursive"
FusionMode fusion_mode_from_id(const std::string& id);  ///< Error(UnknownId)

/// One way to combine exposures as the page's picker lists it (the CLI's --fusion ids).
struct FusionModeInfo {
  std::string id;         ///< fusion_mode_id: "weighted" | "recursive"
  std::string label;      ///< the picker's text
  std::string reference;  ///< core/src/citations.hpp
  std::string about;      ///< how it chooses (the header comment, in one line)
};
/// Every fusion mode, the default (weighted) first.
std::vector<FusionModeInfo> fusion_mode_table();

/// Most exposures one fusion takes (the contributor mask has 16 bits).
constexpr int kMaxExposures = 16;

/// The reliability h(u) of a value at u = (v − n)/(S − n) (see the header comment); 0 at or
/// below the detection threshold u_min.
double reliability_Guarnera2018(Zone zone, double u, double w, double u_min = 0);

/// Per-pixel luminance per channel and where it came from.
struct FusedLuminance {
  int width = 0, height = 0;
  std::vector<float> L;                    ///< width·height·3, L(R), L(G), L(B) in cd/m² (eq 10)
  std::vector<std::uint8_t> source;        ///< dominant exposure per pixel (index into `exposures`), 255: none
  std::vector<std::uint16_t> contributors; ///< bit e: exposure e served the pixel
  std::vector<ExposureSettings> exposures; ///< in the order the frames were given
  std::vector<std::size_t> dominant_pixels;  ///< per exposure: pixels it dominates
  std::size_t saturated_pixels = 0;   ///< a channel saturated in every exposure (NaN)
  std::size_t unreliable_pixels = 0;  ///< no exposure with h > 0 in any channel (too dark)
  std::string make, model;
};

/// Weighted fusion, one frame at a time.
class ExposureFusion {
 public:
  /// `normalisation` and `fit` must outlive the object. width/height: the measurement image.
  ExposureFusion(const Normalisation& normalisation, const LuminanceFit& fit, int width, int height);
  /// Adds a frame. FrameMismatch if its size, make or model differs from the first frame's (or
  /// its size from the fall-off fit's); LimitExceeded beyond kMaxExposures frames.
  void add(const RawImage& frame, const ExposureSettings& exposure);
  /// The fused luminance. NoUsableData when no pixel had a reliable value in any exposure
  /// (every frame dark, or saturated); InvalidArgument if no frame was added.
  FusedLuminance finish();

 private:
  const Normalisation& n_;
  const LuminanceFit& fit_;
  FusedLuminance out_;
  std::vector<float> sum_wL_, sum_w_, best_;
  std::shared_ptr<const detail::FusionTables> tables_;  // built with the first frame
};

/// Algorithm 1 on frames held in memory (same checks as ExposureFusion::add). `guess`: index of
/// {t_g, N_g} in `frames`; −1: the exposure of median ε.
FusedLuminance select_exposures_Guarnera2018(const std::vector<const RawImage*>& frames,
                                             const std::vector<ExposureSettings>& exposures,
                                             const Normalisation& normalisation, const LuminanceFit& fit,
                                             int guess = -1);

}  // namespace tristim

// The absolute tele-colorimeter (Guarnera, Bianco & Schettini 2018), the whole chain:
//   eq (4):  [X, Y, Z]ᵀ cd/m² = M · T([L(R), L(G), L(B)])ᵀ
// with L from eqs (7), (8), (10) (luminance.hpp, fusion.hpp) and M fitted on chromatic stimuli
// by the pattern search of eqs (11)-(12), Algorithm 2, for T = T1 (eq 13), To (eq 14) or T2R
// (eq 15) — the characterisation stage's fit_Guarnera2018 with Objective::PatternSearch.
//
// An AbsoluteProfile holds everything needed to turn a bracketed series of RAW frames of the
// same camera into X, Y, Z maps in cd/m²; it is written as versioned JSON
// ("format": "tristim-absolute-profile", "version": 1; every double with 17 significant digits,
// so a profile read back gives bit-identical results). Since recipes exist it also holds the
// recipe it was made with ("recipe", absolute/recipe.hpp) and the training figures ("training");
// profiles without them are still read.
#pragma once
#include <string>
#include <vector>

#include "tristim/absolute/fusion.hpp"
#include "tristim/absolute/luminance.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"
#include "tristim/methods.hpp"

namespace tristim {

constexpr int kAbsoluteProfileVersion = 1;

// ---- evaluation as in section 4.1 ----------------------------------------------------------

/// Eq (16): the white patch's XYZ scaled to the largest luminance Y_Q seen in the scene,
/// [X_w·Y_Q/Y_w, Y_Q, Z_w·Y_Q/Y_w] cd/m² (Experiment b).
Vec3 white_Guarnera2018(const Vec3& white_patch_XYZ, double max_luminance);
/// Illuminant E at the largest luminance: X = Y = Z = Y_max (Experiments a and c).
Vec3 white_equal_energy(double max_luminance);

struct AbsoluteMetrics {
  Metrics metrics;                  ///< ΔE94, ΔE00 (Lab relative to `white`), NRMSE per X, Y, Z, …
  double relative_Y_error = 0;      ///< mean over Y_ref > 0 of |Y_est − Y_ref|/Y_ref
  Vec3 median_absolute_error = Vec3::Zero();  ///< median |est − ref| per X, Y, Z, cd/m²
  Vec3 white = Vec3::Zero();
};
AbsoluteMetrics evaluate_absolute(const PatchMatrix& estimated_XYZ, const PatchMatrix& reference_XYZ,
                                  const Vec3& white);

/// The fitted chain on its own training stimuli (section 4.1 figures with the white E at their
/// largest Y, as Experiments a and c): what the fit used and how well it reproduces them.
struct AbsoluteTraining {
  int luminance_stimuli = 0;  ///< equal-tristimulus stimuli given (eq 8)
  int colour_stimuli = 0;     ///< chromatic stimuli the colour matrix was fitted on (eqs 11-15)
  int saturated_stimuli = 0;  ///< left out: a channel in the saturated zone
  int evaluated = 0;          ///< unsaturated stimuli the figures cover
  AbsoluteMetrics figures;
};


struct AbsoluteProfile {
  int version = kAbsoluteProfileVersion;
  std::string make, model;                ///< the camera (frames from another are refused)
  int width = 0, height = 0;              ///< measurement image size (0: any; set with a fall-off)
  Normalisation normalisation;            ///< n, S, A_R/A_G/A_B, f(r), w (eq 7, zones)
  SaturationEstimate saturation;          ///< how S was found
  std::string areas_source = "none";      ///< "camera:<name>", "file:<name>", "estimated", "none"
  LuminanceFit luminance;                 ///< eq (8) per channel + reciprocity report
  std::string transform = "T1";           ///< T1 | To | T2R (eqs 13-15)
  Model colour;                           ///< M (3 × P), model id "Guarnera2018-<transform>"
  FitStatus colour_status = FitStatus::Ok;
  std::string colour_message;             ///< e.g. "no chromatic stimuli: M = identity"
  int colour_stimuli = 0;
  double colour_objective = 0;            ///< eq (11) at the optimum, cd/m²
  FusionMode fusion = FusionMode::Weighted;
  /// The recipe it was made with (absent in profiles written before recipes existed).
  bool has_recipe = false;
  AbsoluteRecipe recipe;
  /// The chain on its own training stimuli, recorded at fit time (absent in older profiles).
  bool has_training = false;
  AbsoluteTraining training;
  /// The linearisation stage as a recipe names it: the `Guarnera2018` table row with n and S
  /// (green's) and the areas of this profile; exposure options at their defaults (ε = 1, i.e.
  /// exposure units; the k's are in `luminance`, relative to luminance.iso_reference).
  MethodChoice linearisation_choice() const;
  /// eq (4) for one pixel's L(R), L(G), L(B).
  Vec3 XYZ(const Vec3& L) const;
};

struct AbsoluteFitOptions {
  LuminanceFitOptions luminance;
  std::string transform = "T1";   ///< T1 | To | T2R
  PatternSearchOptions psm;       ///< Algorithm 2's settings
  /// Also fit M on the equal-tristimulus stimuli (they pin the neutral axis); the paper uses
  /// only the 24 chromatic ones.
  bool colour_with_luminance_set = false;
};

/// Fits the luminance module (section 3.1) on the stimuli with luminance_set, then M (section
/// 3.2) on the others (their L from the fitted curves). Without chromatic stimuli M is the
/// identity (eq 9: X = Y = Z = L for equal-tristimulus light) and colour_message says so.
/// Errors: those of fit_luminance_Guarnera2018 and of the characterisation fit (UnknownId for a
/// transform other than T1/To/T2R, TooFewPatches, …).
AbsoluteProfile fit_absolute_Guarnera2018(const std::vector<TrainingStimulus>& stimuli,
                                          const Normalisation& normalisation,
                                          const AbsoluteFitOptions& options = {});

/// X, Y, Z maps in cd/m² and where each pixel's values came from.
struct AbsoluteImage {
  FusedLuminance luminance;  ///< L(R), L(G), L(B), source and contributor maps, counts
  std::vector<float> XYZ;    ///< width·height·3, cd/m² (NaN where saturated in every exposure)
};

/// Applies the profile to one or more frames of a scene (same camera and size; exposure from
/// each frame's metadata unless `exposures` gives them, one per frame). Weighted mode streams
/// the frames through ExposureFusion; recursive mode is Algorithm 1. Errors: FrameMismatch
/// (another camera than the profile's or the series', another size), MissingMetadata,
/// NoUsableData, LimitExceeded (more than 16 frames).
AbsoluteImage apply_absolute(const AbsoluteProfile& profile, const std::vector<const RawImage*>& frames,
                             const std::vector<ExposureSettings>& exposures = {});
/// FrameMismatch unless the frame comes from the profile's camera and (when the profile has a
/// size) has its size.
void check_profile_frame(const AbsoluteProfile& profile, const RawImage& frame, const std::string& what);
/// eq (4) over a whole L image in place of XYZ (width·height·3 each; NaN stays NaN).
void luminance_to_XYZ(const AbsoluteProfile& profile, const std::vector<float>& L, std::vector<float>& XYZ);

// ---- JSON ------------------------------------------------------------------------------------

/// The section 4.1 figures as JSON: {"metrics": metrics_json(…), "relative_Y_error",
/// "median_absolute_error": [X, Y, Z], "white": [X, Y, Z]} (non-finite numbers as null), and back.
json::Value absolute_metrics_json(const AbsoluteMetrics& metrics);
AbsoluteMetrics absolute_metrics_from_json(const json::Value& value, const std::string& where);
/// The training figures as the profile and the report write them, and back.
json::Value absolute_training_json(const AbsoluteTraining& training);
AbsoluteTraining absolute_training_from_json(const json::Value& value, const std::string& where);
/// A fall-off fit as the profile writes it (p1, p2, p3, centre, r_scale, size, bins, residuals).
json::Value falloff_fit_json(const FalloffFit& falloff);

json::Value absolute_profile_json(const AbsoluteProfile& profile);
std::string absolute_profile_to_json(const AbsoluteProfile& profile);
/// Error(ProfileVersion) for another version; Error(ProfileInvalid) for anything else wrong.
AbsoluteProfile absolute_profile_from_json(const std::string& text);

}  // namespace tristim

// From an absolute recipe and its frames to a profile, and from a profile and a bracketed series
// to maps and a report: the one data path the CLI (`tristim absolute fit|apply|evaluate`) and the
// page share (the absolute counterpart of profile/characterise.hpp).
//
//   recipe (stimuli rows, options) + frames (bracket, lens cap, flat) ─→ characterise_absolute
//     → profile (embeds the recipe and the training figures), OECF panels (fig 5), report
//   profile + bracket ─→ apply_absolute_series → maps ─→ absolute_report(test rows) → report
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/absolute/report.hpp"

namespace tristim {

/// The decoded frames a recipe names, in its order.
struct AbsoluteFrames {
  std::vector<const RawImage*> bracket;     ///< one per recipe.inputs.bracket
  std::vector<const RawImage*> lens_cap;    ///< one per recipe.inputs.lens_cap
  const RawImage* flat = nullptr;           ///< when recipe.inputs.flat names one
  /// Frames that region rows name outside the bracket (e.g. photos of a training chart), by name.
  std::vector<std::string> other_names;
  std::vector<const RawImage*> others;
};

/// The frame a row's `file` names among `names`: the same text, else the only one with the same
/// last path component ("train_1.dng" names "/data/train_1.dng"); −1 when none (or two) match.
int find_frame(const std::vector<std::string>& names, const std::string& file);

/// One exposure of fig 5: the normalised R', G', B' (eq 7) of the luminance training stimuli
/// against Y (cd/m²), the common eq (8) curve at its ε and the exposure's own fit.
struct OecfPanel {
  ExposureSettings exposure;
  std::string label;
  double factor = 0;                                   ///< ε relative to the reference ISO
  bool parallel = true;                                ///< the reciprocity check of this exposure
  std::array<int, 3> samples{};
  std::array<double, 3> scale_ratio{}, slope_difference{}, rms_relative{};
  std::array<std::vector<double>, 3> point_Y, point_R; ///< the training stimuli (Y > 0, R' > 0)
  std::array<std::vector<double>, 3> curve_Y, curve_R; ///< the common curve at this ε
  std::array<std::vector<double>, 3> own_Y;            ///< the exposure's own fit at curve_R (empty: none)
};
std::vector<OecfPanel> oecf_panels(const AbsoluteProfile& profile, const std::vector<TrainingStimulus>& stimuli);

struct AbsoluteCharacterisation {
  AbsoluteRecipe recipe;                  ///< completed
  AbsoluteProfile profile;                ///< embeds the recipe and the training figures
  std::vector<TrainingStimulus> stimuli;  ///< as fitted (regions sampled, saturated flags set)
  std::vector<OecfPanel> panels;          ///< fig 5, shortest exposure first
  AbsoluteReport report;                  ///< fit and training
};

/// Fits the profile of `recipe` (fit_absolute_from_frames: eq 7 from the frames, eq 8 across
/// every exposure, the colour matrix) and evaluates it on its training stimuli. Errors: those of
/// complete_absolute_recipe and of the fit; InvalidArgument (a frame count that differs from the
/// names, a named flat without its frame); UnknownId (a region row naming a file that is neither in
/// the bracket nor among the other frames); TooFewPatches (fewer than 3 equal-tristimulus stimuli).
AbsoluteCharacterisation characterise_absolute(const AbsoluteRecipe& recipe, const AbsoluteFrames& frames);

// ---- applying a profile to a bracketed series ----------------------------------------------

struct AbsoluteApplyOptions {
  std::string mode;                         ///< "" (the profile's), "weighted" or "recursive"
  std::vector<ExposureSettings> exposures;  ///< per frame (t or N 0: from its metadata), or none
  std::vector<std::string> names;           ///< the frames' files (messages; what region rows name)
};

/// Progress of a long step: fraction done (0..1) and what is being done.
using AbsoluteProgress = std::function<void(double, const std::string&)>;

/// A profile applied to a series: X, Y, Z maps and where they came from.
struct AbsoluteMaps {
  AbsoluteProfile profile;          ///< as applied (its fusion mode set)
  AbsoluteImage image;
  std::vector<std::string> names;   ///< one per frame ("frame 1", … when not given)
};

/// How messages name frame i of a series: "'name'" or "frame i+1".
std::string series_frame_name(const std::vector<std::string>& names, size_t i);
/// The exposure of a frame: `given` when it has t and N, else the frame's metadata
/// (MissingMetadata naming `name`).
ExposureSettings frame_exposure(const RawImage& frame, const std::string& name, const ExposureSettings& given = {});
/// The exposure of every frame of a series, after checking that the frames share one camera and
/// size (every camera and size first, then the metadata). InvalidArgument (no frames, a count of
/// exposures other than 0 or one per frame), LimitExceeded (more than kMaxExposures frames).
std::vector<ExposureSettings> series_exposures(const std::vector<const RawImage*>& frames,
                                               const AbsoluteApplyOptions& options);
/// Checks the series (series_exposures, check_profile_frame) and fuses it: weighted, one frame at a
/// time (progress per frame), or Algorithm 1; then eq (4).
AbsoluteMaps apply_absolute_series(const AbsoluteProfile& profile, const std::vector<const RawImage*>& frames,
                                   const AbsoluteApplyOptions& options = {}, const AbsoluteProgress& progress = {});

/// The mean X, Y, Z over the finite pixels of a window × window square around (x, y) (clipped at
/// the borders); `count` = pixels averaged (0: NaN). InvalidArgument for a point outside the image.
Vec3 window_mean(const AbsoluteImage& image, int x, int y, int window, int& count);

/// What the pointer reads at a pixel.
struct AbsoluteReadout {
  int x = 0, y = 0, n = 0;         ///< the window's centre and finite pixels averaged
  Vec3 XYZ = Vec3::Constant(NAN);  ///< mean over the window, cd/m²
  Vec3 L = Vec3::Constant(NAN);    ///< L(R), L(G), L(B) at the centre, cd/m² (eq 10)
  int source = -1;                 ///< dominant exposure at the centre, −1: none
  std::string source_label;
  std::vector<int> contributors;   ///< exposures that served the centre pixel
};
AbsoluteReadout absolute_readout(const AbsoluteMaps& maps, int x, int y, int window = 1);

AbsoluteMapsSummary absolute_maps_summary(const AbsoluteMaps& maps);

// ---- the report ------------------------------------------------------------------------------

struct AbsoluteEvaluateOptions {
  /// The CIELAB white of the test figures (section 4.1): "" the brightest chromatic test stimulus
  /// as the white patch, eq (16), or E when there is none; "E": X = Y = Z = Y_Q (Experiments a,
  /// c); a test stimulus id: that stimulus as the white patch, eq (16) (UnknownId if absent).
  std::string white;
};

/// The test scene's rows and figures. Region rows are measured on `maps` (required when there are
/// any: InvalidArgument otherwise) and must name one of its frames (UnknownId); a region outside
/// the maps is InvalidArgument.
AbsoluteTestReport evaluate_absolute_test(const AbsoluteProfile& profile, const AbsoluteMaps* maps,
                                          const std::vector<AbsoluteStimulus>& test, const AbsoluteEvaluateOptions& options = {});

/// The report: the profile's fit and training figures, the maps' summary (when given) and the
/// test scene (when `test` has rows; their sets completed by the 2 % rule).
AbsoluteReport absolute_report(const AbsoluteProfile& profile, const AbsoluteMaps* maps,
                               const std::vector<AbsoluteStimulus>& test = {}, const AbsoluteEvaluateOptions& options = {});
/// The report of the maps' own profile.
AbsoluteReport absolute_maps_report(const AbsoluteMaps& maps, const std::vector<AbsoluteStimulus>& test = {},
                                    const AbsoluteEvaluateOptions& options = {});

}  // namespace tristim

// Versioned profile JSON: a fitted model with everything needed to use and trust it.
//
// Format (version 1), every double written with 17 significant digits so that reading the
// profile back reproduces every prediction bit for bit:
// {
//   "format": "tristim-profile", "version": 1, "tristim_version": "0.1.0",
//   "model": {"id": "Finlayson2015-2", "n_terms": 6, "terms": ["R", ...],
//             "coefficients": [[...P...], [...], [...]]},          // 3 × P, XYZ = M·φ(RGB)
//   "objective": "ls" | "psm" | "de2000",
//   "colorimetry": {"white": [X, Y, Z], "illuminant": "D50", "observer": "CIE 1931 2°"},
//   "white_preservation": {"enabled": false, "patch": "", "RGB": [...], "XYZ": [...]},
//   "training": {"patches": 24, "digest": "fnv1a64:<16 hex digits>", "rgb_max": 13000},
//   "fit": {"status": "ok", "message": "", "condition_number": ..., "iterations": ...,
//           "objective_value": ...},
//   "metrics": {"training": {...}, "loo": {...}},                  // summaries (optional)
//   "recipe": {...},                                               // how it was made (recipe.hpp; optional)
//   "linearisation": {...}                                         // fitted OECF (optional, see below)
// }
// A profile fitted on non-linear data (JPEG/TIFF/PNG, a `--linearisation` other than identity)
// carries its fitted linearisation stage (linearisation_json): its input is then the stored
// camera values, which profile_predict and apply_profile linearise before the model. Its training
// digest is over those stored values.
// The training digest is FNV-1a 64-bit (not cryptographic: it identifies the data, it does
// not authenticate it) over "tristim-training-v1\n" followed, per patch, by the id bytes, a
// NUL, and R, G, B, X, Y, Z as IEEE-754 little-endian doubles.
#pragma once
#include <string>
#include <vector>

#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/profile/recipe.hpp"

namespace tristim {

constexpr int kProfileVersion = 1;

struct Profile {
  int version = kProfileVersion;
  std::string tristim_version;
  Model model;
  Objective objective = Objective::LeastSquares;
  Vec3 white = whites::D50();
  std::string illuminant = "D50";
  std::string observer = "CIE 1931 2°";
  bool white_preserved = false;
  std::string white_patch;
  Vec3 white_RGB = Vec3::Zero(), white_XYZ = Vec3::Zero();
  int training_patches = 0;
  std::string training_digest;
  double rgb_max = 1;  ///< largest training camera RGB value (device 1.0 of ICC/.cube exports)
  /// The training patches themselves (characterise() keeps them; profiles written before have none):
  /// the labels as the user's data spell them, the camera RGB as sampled (before the linearisation
  /// stage) and the reference XYZ as given (before a surface correction). With them a profile alone
  /// is enough to make a reproducible link (tristim share --profile p.json).
  bool has_training_data = false;
  std::vector<std::string> training_labels;
  PatchMatrix training_camera_RGB, training_reference_XYZ;
  FitStatus status = FitStatus::Ok;
  std::string message;
  double condition_number = 0;
  int iterations = 0;
  double objective_value = 0;
  json::Value metrics;  ///< object; empty object when not computed
  bool has_recipe = false;  ///< profiles written before recipes existed have none
  Recipe recipe;            ///< how the profile was made (profile/recipe.hpp)
  bool has_linearisation = false;  ///< the input is stored (non-linear) values: see the header comment
  Linearisation linearisation;     ///< the fitted linearisation stage (when has_linearisation)
};

/// The model's input for stored camera RGB: linearised by the profile's linearisation stage
/// when it has one, else camera_RGB as it is.
PatchMatrix profile_input(const Profile& profile, const PatchMatrix& camera_RGB);
/// XYZ predicted by the profile for camera RGB as the profile takes it (stored values when it
/// carries a linearisation, linear camera RGB otherwise).
PatchMatrix profile_predict(const Profile& profile, const PatchMatrix& camera_RGB);

/// The FitStatus a profile names (fit_status_name's spelling); Error(ProfileInvalid) otherwise.
FitStatus fit_status_from_name(const std::string& name);

struct Image3f;  // profile/export.hpp
/// apply_profile (profile/export.hpp) on an image given as 3·width·height linear camera-RGB
/// values, checked: InvalidArgument for a size that is not positive, RowLength for another count.
Image3f apply_profile_to_pixels(const Profile& profile, const std::vector<float>& rgb, int width, int height);

/// "fnv1a64:xxxxxxxxxxxxxxxx" of the training data (see the header comment).
std::string training_digest(const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                            const PatchMatrix& reference_XYZ);

/// A profile from a fit and its evaluation. `ids` may be empty (then "1".."N" are digested).
/// `illuminant` empty: "D50"/"D65" when the white has that chromaticity (to 1e-4), else "custom".
Profile make_profile(const ModelEvaluation& evaluation, const FitOptions& options,
                     const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                     const PatchMatrix& reference_XYZ, const std::string& white_patch = "",
                     const std::string& illuminant = "");

/// "fnv1a64:xxxxxxxxxxxxxxxx" of arbitrary bytes (an uploaded reference file, a held-out set).
std::string bytes_digest(const std::string& bytes);

/// The profile document (format, version, then Profile's field list) and its text.
json::Value profile_json(const Profile& profile);
std::string profile_to_json(const Profile& profile);
/// Error(ProfileVersion) for another version, Error(ProfileInvalid) for text that is not
/// JSON, not a tristim profile, missing or unknown fields, an unknown model or a wrong coefficient
/// shape; an embedded recipe is read strictly (recipe_from_json's codes).
Profile profile_from_json(const std::string& text);
/// The same from the parsed document (a JS caller's object).
Profile profile_from_document(const json::Value& document);

/// Summaries (and, with per_patch, the per-patch arrays) as a JSON object.
json::Value summary_json(const Summary& s);
json::Value metrics_json(const Metrics& m, const std::vector<std::string>& ids = {}, bool per_patch = false);

}  // namespace tristim

/// The profile's members (io/fields.hpp), defined in profile.cpp: a profile crosses to JS as its
/// document (wasm/types.hpp).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(Profile);
}  // namespace tristim::fields

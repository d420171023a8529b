// An AbsoluteRecipe: everything that decides how an absolute profile (Guarnera, Bianco & Schettini
// 2018, the tele-colorimeter) is made, as a value — the absolute counterpart of profile/recipe.hpp.
//
//   inputs:  the training stimuli (rows), the bracketed series, lens-cap frames, the flat field
//            (named by file; the decoded frames come with characterise_absolute), the sensitivities
//   options: the colour transform (eqs 13-15), the exposure fusion, the zone parameter w (section
//            3.1), the noise floor and saturation when no frame gives them (eq 7)
//
// Same recipe + same frames → the same profile, natively and in wasm. The profile JSON embeds the
// recipe it was made with (absolute/profile.hpp); `tristim absolute fit --recipe r.json` reads one.
//
// JSON (version 1), every double with 17 significant digits (exact round trip):
// {
//   "format": "tristim-absolute-recipe", "version": 1,
//   "inputs": {
//     "stimuli": [{"id": "Y30@1", "set": "luminance", "exposure": [t, N, ISO], "file": "",
//                  "region": [x, y, w, h], "RGB": [R, G, B], "falloff": 1, "XYZ": [X, Y, Z]}, ...],
//     "bracket": ["scene_1.dng", ...], "lens_cap": ["cap_1.dng", ...], "flat": "flat.dng",
//     "sensitivities": {"choice": "none" | "camera" | "given", "camera": "Canon_EOS_5D_Mark_II",
//                       "source": "file:ssf.csv", "wavelengths": [...], "R": [...], "G": [...], "B": [...]}
//   },
//   "options": {"transform": "T1", "fusion": "weighted", "w": 10, "noise_floor": 0, "saturation": 0}
// }
// A stimulus row is per patch (file "": RGB, falloff and exposure are the measurement) or a region
// of a frame (file and region; exposure zeros: from the frame's metadata). Unknown fields, a wrong
// type or another version are refused (RecipeInvalid / RecipeVersion naming the field).
#pragma once
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "tristim/absolute/normalisation.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/json.hpp"
#include "tristim/methods.hpp"

namespace tristim {

constexpr int kAbsoluteRecipeVersion = 1;

/// One training or test stimulus as a user gives it (a row of the stimuli CSV, stimuli_file.hpp).
struct AbsoluteStimulus {
  std::string id;
  std::string set;              ///< "luminance" | "colour" (completion: "" by the 2 % rule, "oecf", "color")
  ExposureSettings exposure;    ///< per patch: t, N, ISO of the shot; region: zeros = from the frame
  Vec3 RGB = Vec3::Zero();      ///< per patch: black-subtracted DN
  double falloff = 1;           ///< per patch: f(r) of eq (7)
  std::string file;             ///< region: the frame file it names ("": per patch)
  int x = 0, y = 0, w = 0, h = 0;  ///< region, measurement pixels
  Vec3 XYZ = Vec3::Zero();      ///< measured, cd/m²
  int line = 0;                 ///< CSV line it came from, for messages (not part of the recipe JSON)
  bool region() const { return !file.empty(); }
};

/// A stimuli CSV as rows (read_stimuli_csv's rules and errors; sets completed).
std::vector<AbsoluteStimulus> read_absolute_stimuli(std::string_view text, const std::string& source);
/// Rows as a stimuli CSV that read_absolute_stimuli reads back exactly (17 significant digits):
/// id, set, exposure_s, f_number, iso, file, x, y, w, h, R, G, B, falloff, X, Y, Z (a region row
/// leaves R, G, B, falloff empty, a per-patch row file, x, y, w, h).
std::string absolute_stimuli_to_csv(const std::vector<AbsoluteStimulus>& rows);
/// How messages name a row: "stimulus 'Y30@1'" with " (line 5)" when it came from a file.
std::string stimulus_where(const AbsoluteStimulus& row);

/// Where the channel areas A_R, A_G, A_B of eq (7) come from.
struct AbsoluteSensitivities {
  std::string choice = "none";  ///< absolute_sensitivity_table(): "none" (A = 1, 1, 1) | "camera" (built in) | "given" (ssf)
  std::string camera;           ///< a built-in camera (camera_names()) for "camera"
  std::string source;           ///< what given curves are: "file:ssf.csv", "estimate:Jiang2013 …"
  SpectralData ssf;             ///< the given curves: three columns R, G, B
};

struct AbsoluteInputs {
  std::vector<AbsoluteStimulus> stimuli;  ///< training: luminance set (eq 8) and colour set (eqs 11-15)
  std::vector<std::string> bracket;       ///< the scene's series (S is measured on it too)
  std::vector<std::string> lens_cap;      ///< averaged: n and σ of eq (7)
  std::string flat;                       ///< equal-tristimulus flat field: f(r) of eq (7) ("": none)
  AbsoluteSensitivities sensitivities;
};

struct AbsoluteOptions {
  std::string transform = "T1";     ///< T1 | To | T2R (eqs 13-15)
  std::string fusion = "weighted";  ///< weighted | recursive (Algorithm 1), fusion.hpp
  double w = 10;                    ///< zone parameter, section 3.1 (Z_c = [1/w, (w−1)/w])
  double noise_floor = 0;           ///< n in DN when there are no lens-cap frames
  double saturation = 0;            ///< S in DN; 0: measured from the frames
};

struct AbsoluteRecipe {
  int version = kAbsoluteRecipeVersion;
  AbsoluteInputs inputs;
  AbsoluteOptions options;
};

/// The options' ranges as the method tables state them (the page's inputs and --help read them):
/// transform (choice), fusion (choice), w (> 2: Z_c must not be empty), noise_floor, saturation.
std::vector<OptionSpec> absolute_option_table();

/// Where A_R, A_G, A_B of eq (7) come from: AbsoluteSensitivities::choice takes exactly these ids
/// (none, given, camera — in the order the page's picker lists them; each row cites what it uses).
std::vector<MethodInfo> absolute_sensitivity_table();

/// Checks ids, options and rows and returns the recipe with every row's set completed ("" by the
/// 2 % rule) and the sensitivities' defaults. Errors: RecipeVersion; InvalidArgument (an option
/// out of its range, a set other than luminance/colour, a region row without a positive size, a
/// given set of sensitivities without three curves); UnknownId (transform, fusion, camera);
/// MissingMetadata (a per-patch row without exposure time and f-number).
AbsoluteRecipe complete_absolute_recipe(const AbsoluteRecipe& recipe);

/// The recipe as JSON (see the header comment); written completed.
json::Value absolute_recipe_json(const AbsoluteRecipe& recipe);
std::string absolute_recipe_to_json(const AbsoluteRecipe& recipe);
/// Strict reader: RecipeVersion, RecipeInvalid (not JSON, unknown or missing field, wrong type),
/// and complete_absolute_recipe's errors.
AbsoluteRecipe absolute_recipe_from_json(const json::Value& value);
AbsoluteRecipe absolute_recipe_from_json(const std::string& text);

}  // namespace tristim

// A Recipe: everything that decides how a characterisation is made, stage by stage, as a value.
//
//   reference → capture → sampling → linearisation → surface → characterisation → evaluation
//
// Same recipe + same input data (the chart image or patch tables, the reference data) → the same
// profile, natively and in wasm. The profile JSON embeds the recipe it was made with; the CLI
// (`tristim fit --recipe r.json`) and the page's session both hold one.
//
// JSON (version 1), every double with 17 significant digits (exact round trip):
// {
//   "format": "tristim-recipe", "version": 1,
//   "reference": {"chart": "passport", "data_digest": "", "illuminant": "D50", "observer": "1931"},
//   "capture": {"dark_frames": 0, "dark_mode": "per_pixel", "flat_field": false,
//               "falloff": false, "saturation": 0, "noise_floor": 0,
//               "light_trap": [x1, y1, ... x4, y4], "flare": [R, G, B]},   (both only with a light trap)
//   "sampling": {"layout": {"chart": "passport", "rows": 0, "columns": 0, "margins": [l, t, r, b],
//                           "gap": -1},
//                "corners": [x1, y1, ... x4, y4], "area": 0.5, "exclude": ["A3"],
//                "exclude_flagged": false,
//                "exclude_flags": ["saturated"],        (only when not empty)
//                "missing": ["C1", …]},                  (only when not empty: a chart cut by the frame)
//   "linearisation": {"method": "identity", "parameters": {}, "settings": {}},
//   "surface": {"method": "none", "parameters": {}, "settings": {}},
//   "characterisation": {"model": "Finlayson2015-2",
//                        "objective": {"method": "psm", "parameters": {...}, "settings": {}},
//                        "white_patch": "D1", "lab_white": [X, Y, Z]},
//   "evaluation": {"leave_one_out": true, "held_out_digest": ""},
//   "images": [{"name": "a.dng", "sha256": "…", "reference": {…}, "capture": {…},    (only with images)
//               "sampling": {…}, "candidate": "all"}, …],
//   "duplicates": "once"                                                         (only with images)
// }
// A recipe with `images` trains one fit on the union of several chart images (issue 48; each entry
// its own capture, reference and sampling, which default to the recipe's own stages when absent).
// A recipe without them reads, writes and fits exactly as before.
// Unknown fields, a wrong type, an unknown method id or option, or another version are refused
// with RecipeInvalid / RecipeVersion / UnknownId naming the field.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/characterisation/fit.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"
#include "tristim/methods.hpp"

namespace tristim {

constexpr int kRecipeVersion = 1;

/// Where the reference colours come from.
struct ReferenceStage {
  std::string chart = "cc24";      ///< a built-in chart id (list_charts()), or "file" for uploaded data
  std::string data_digest;         ///< "fnv1a64:…" of uploaded reference data ("" for a built-in chart)
  std::string illuminant = "D50";  ///< illuminant_spd() id (A, D50, D65, F11, D4000, …)
  std::string observer = "1931";   ///< "1931" | "1964"
};

/// Frame calibration settings (capture/calibration.hpp). The frames themselves are inputs.
struct CaptureStage {
  int dark_frames = 0;                   ///< how many dark frames were averaged (0: none)
  std::string dark_mode = "per_pixel";   ///< "per_pixel" | "per_channel" (dark_mode_id; the aliases
                                         ///< "pixel" | "channel" are read and completed to these)
  bool flat_field = false;               ///< a flat field was applied
  bool falloff = false;                  ///< the radial fall-off fit (Guarnera eq 7) replaced the flat
  double saturation = 0;                 ///< clip level in DN; 0: LibRaw's maximum. A TIFF/PNG/JPEG
                                         ///< (stored, non-linear values): the encoding's full scale,
                                         ///< 255 or 65535, which the linearisation stage reads as x = 1
  double noise_floor = 0;                ///< DN; 0: from the dark frames (or none)
  /// An in-scene light trap (Abed 2013 App. C step 1, chart/light_trap.hpp): its four corners in
  /// the chart image (all 0: none) and the flare measured there (mean RGB after the dark frame,
  /// DN), subtracted per channel before sampling. With --raw, `fit --recipe` measures it again.
  std::array<double, 8> light_trap{};
  std::array<double, 3> flare{};
  bool has_light_trap() const {
    for (double v : light_trap) if (v != 0) return true;
    return false;
  }
};

/// How patches were read from the image.
struct SamplingStage {
  LayoutOptions layout;                  ///< chart grid (chart/layout.hpp)
  std::array<double, 8> corners{};       ///< x1,y1 … x4,y4 clockwise from A1 (all 0: not from an image)
  double area = 0.5;                     ///< sampled fraction of each patch side
  std::vector<std::string> exclude;      ///< patch ids left out of the fit
  bool exclude_flagged = false;          ///< also leave out every flagged patch (every row of sample_flag_table())
  /// Also leave out the patches with any of these flags (sample_flag_table() ids, in its order:
  /// completion sorts them and refuses an unknown one). Empty: none by its flags (an older recipe,
  /// or the page's toggles all off); written only when not empty, so older recipes stay as they were.
  std::vector<std::string> exclude_flags;
  /// The patches of a chart cut by the frame that were not sampled (ChartSample::missing, their
  /// normalised ids in layout order): a record of the sample the fit was made on — characterise()
  /// sets it from a sampled training set — not an instruction. Written only when not empty.
  std::vector<std::string> missing;
};

/// The flags sample_chart() puts on a patch (chart/layout.hpp: "saturated", "dark", "nonuniform"),
/// one "boolean" OptionSpec row each, named by the flag: its label is the page's toggle, its
/// default (1: left out) the page's starting choice, which a fresh session's recipe writes in
/// sampling.exclude_flags. `tristim models --json` lists them ("sample_flags").
std::vector<OptionSpec> sample_flag_table();

/// Whether a patch with these flags is left out by `sampling` (exclude_flagged: any flag;
/// exclude_flags: one of those), and the flags that leave it out ("" when kept).
std::string excluding_flags(const SamplingStage& sampling, const std::vector<std::string>& flags);

/// Model, objective and their options.
struct CharacterisationStage {
  std::string model = "matrix-3x3";      ///< model_table() id
  MethodChoice objective{"ls", {}, {}};  ///< objective_table() row and its options
  std::string white_patch;               ///< preserved exactly when set (e.g. "D1")
  Vec3 lab_white = whites::D50();        ///< white of the CIELAB errors and the de2000 objective
};

/// What is reported next to the fit.
struct EvaluationStage {
  bool leave_one_out = true;
  std::string held_out_digest;           ///< training_digest() of a held-out patch set ("" none)
};

/// One chart image of a recipe that trains on several (issue 48): its own capture settings (light
/// trap), reference and sampling (layout; corners, or none to detect the chart).
struct RecipeImage {
  std::string name;                      ///< the image file's name as given (messages, the profile)
  std::string sha256;                    ///< SHA-256 of the image file, 64 hex digits ("" until read)
  ReferenceStage reference;
  CaptureStage capture;
  SamplingStage sampling;                ///< corners all 0: the chart is detected (chart/detect.hpp)
  /// Which detected chart(s) to sample: "" (sampling.corners, or the best candidate when they are
  /// all 0), "all" (every candidate: two charts in one image), or a candidate index "0", "1", …
  /// (written as a JSON number).
  std::string candidate;
};

/// How patches of the same colour (same patch id and the same reference XYZ) in several images count.
inline constexpr const char* kDuplicatesOnce = "once";  ///< merged into one row, camera RGB averaged
inline constexpr const char* kDuplicatesEach = "each";  ///< every shot its own row (the plain union)

struct Recipe {
  int version = kRecipeVersion;
  ReferenceStage reference;
  CaptureStage capture;
  SamplingStage sampling;
  MethodChoice linearisation{"identity", {}, {}};
  MethodChoice surface{"none", {}, {}};
  CharacterisationStage characterisation;
  EvaluationStage evaluation;
  std::vector<RecipeImage> images;       ///< empty: one image (the stages above) or patch tables
  std::string duplicates = kDuplicatesOnce;  ///< kDuplicatesOnce | kDuplicatesEach (with images)
};

/// The recipe as a JSON value / text (see the header comment). Method choices are written
/// complete (every option with its value), so a recipe never depends on a later default.
json::Value recipe_json(const Recipe& recipe);
std::string recipe_to_json(const Recipe& recipe);
/// Strict reader: RecipeVersion, RecipeInvalid (not JSON, unknown or missing field, wrong
/// type), UnknownId (unknown chart layout, model or method id or option), InvalidArgument
/// (an option out of bounds).
Recipe recipe_from_json(const json::Value& value);
Recipe recipe_from_json(const std::string& text);

/// Checks every stage's ids and options against the tables and returns the recipe with every
/// method choice completed (defaults filled in).
Recipe complete_recipe(const Recipe& recipe);

/// FitOptions for the characterisation stage: objective and options, lab white, and (when
/// white_patch is set) the white pair taken from the patch with that id in `ids`
/// (Error(UnknownId) if absent). white_index is set to that row, or -1.
FitOptions recipe_fit_options(const Recipe& recipe, const std::vector<std::string>& ids,
                              const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                              int& white_index);

}  // namespace tristim

// The field lists of the recipe and its stages (defined in recipe.cpp): the JSON and the wasm
// binding use them, so JS sees a recipe as its JSON (`version` listed too, `format` not: the
// document writer adds both, the value is the same).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(ReferenceStage);
TRISTIM_FIELDS_DECLARE(CaptureStage);
TRISTIM_FIELDS_DECLARE(SamplingStage);
TRISTIM_FIELDS_DECLARE(CharacterisationStage);
TRISTIM_FIELDS_DECLARE(EvaluationStage);
TRISTIM_FIELDS_DECLARE(RecipeImage);
TRISTIM_FIELDS_DECLARE(Recipe);
}  // namespace tristim::fields

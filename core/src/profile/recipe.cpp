// Recipe: strict versioned JSON, completion against the method tables, fit options.
#include "tristim/profile/recipe.hpp"

#include <algorithm>
#include <cmath>

#include "tristim/capture/calibration.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/fields.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

namespace {

const fields::Context kRecipe{ErrorCode::RecipeInvalid, "recipe: "};
const fields::Document kRecipeDocument{"tristim-recipe", kRecipeVersion, "recipe", ErrorCode::RecipeInvalid,
                                       ErrorCode::RecipeVersion};

}  // namespace

// ---- the field lists: the JSON writer and the strict reader come from these ------------------

namespace fields {

TRISTIM_FIELDS_DEFINE(ReferenceStage, member<&ReferenceStage::chart>("chart"), member<&ReferenceStage::data_digest>("data_digest"),
               member<&ReferenceStage::illuminant>("illuminant"), member<&ReferenceStage::observer>("observer"));

static bool has_light_trap(const CaptureStage& c) { return c.has_light_trap(); }
TRISTIM_FIELDS_DEFINE(CaptureStage, member<&CaptureStage::dark_frames>("dark_frames"), member<&CaptureStage::dark_mode>("dark_mode"),
               member<&CaptureStage::flat_field>("flat_field"), member<&CaptureStage::falloff>("falloff"),
               member<&CaptureStage::saturation>("saturation"), member<&CaptureStage::noise_floor>("noise_floor"),
               // only recipes with a light trap have these (both, checked in recipe_from_json)
               with_shown(member<&CaptureStage::light_trap>("light_trap", false), has_light_trap),
               with_shown(member<&CaptureStage::flare>("flare", false), has_light_trap));

static json::Value margins_json(const LayoutOptions& L) {
  return json::Value(std::vector<double>{L.margin_left, L.margin_top, L.margin_right, L.margin_bottom});
}
static void read_margins(const json::Value& v, LayoutOptions& L, const Context& c, const std::string& path) {
  std::array<double, 4> m{};
  read(v, m, c, path);
  L.margin_left = m[0], L.margin_top = m[1], L.margin_right = m[2], L.margin_bottom = m[3];
}
TRISTIM_FIELDS_DEFINE(LayoutOptions, member<&LayoutOptions::chart>("chart"), member<&LayoutOptions::rows>("rows"),
               member<&LayoutOptions::columns>("columns"), Field<LayoutOptions>{"margins", margins_json, read_margins},
               member<&LayoutOptions::gap>("gap"));

// exclude_flags and missing only when not empty: a recipe without them is written as before.
static bool has_exclude_flags(const SamplingStage& s) { return !s.exclude_flags.empty(); }
static bool has_missing(const SamplingStage& s) { return !s.missing.empty(); }
TRISTIM_FIELDS_DEFINE(SamplingStage, member<&SamplingStage::layout>("layout"), member<&SamplingStage::corners>("corners"),
               member<&SamplingStage::area>("area"), member<&SamplingStage::exclude>("exclude"),
               member<&SamplingStage::exclude_flagged>("exclude_flagged"),
               with_shown(member<&SamplingStage::exclude_flags>("exclude_flags", false), has_exclude_flags),
               with_shown(member<&SamplingStage::missing>("missing", false), has_missing));

TRISTIM_FIELDS_DEFINE(CharacterisationStage, member<&CharacterisationStage::model>("model"),
               member<&CharacterisationStage::objective>("objective"),
               member<&CharacterisationStage::white_patch>("white_patch"),
               member<&CharacterisationStage::lab_white>("lab_white"));

TRISTIM_FIELDS_DEFINE(EvaluationStage, member<&EvaluationStage::leave_one_out>("leave_one_out"),
               member<&EvaluationStage::held_out_digest>("held_out_digest"));

// A candidate index is written as a number, "all" as a string; absent: "".
static bool has_candidate(const RecipeImage& e) { return !e.candidate.empty(); }
static json::Value candidate_json(const RecipeImage& e) {
  if (e.candidate == "all") return e.candidate;
  return std::stoi(e.candidate);
}
static void read_candidate(const json::Value& v, RecipeImage& e, const Context& c, const std::string& path) {
  if (v.is_string() && v.as_string() == "all") {
    e.candidate = "all";
    return;
  }
  int k = 0;
  if (v.is_string()) c.refuse("'" + path + "' must be \"all\" or a candidate index (0, 1, …)");
  read(v, k, c, path);
  if (k < 0) c.refuse("'" + path + "' must not be negative");
  e.candidate = std::to_string(k);
}
TRISTIM_FIELDS_DEFINE(RecipeImage, member<&RecipeImage::name>("name"), member<&RecipeImage::sha256>("sha256", false),
               member<&RecipeImage::reference>("reference", false), member<&RecipeImage::capture>("capture", false),
               member<&RecipeImage::sampling>("sampling", false),
               with_shown(Field<RecipeImage>{"candidate", candidate_json, read_candidate, nullptr, false}, has_candidate));

static void check_light_trap(const json::Value& capture, const CaptureStage& c, const std::string& path) {
  if (capture.find("light_trap") || capture.find("flare")) {  // optional, but the two together
    if (!capture.find("light_trap") || !capture.find("flare"))
      kRecipe.refuse(path + "light_trap and " + path + "flare go together");
    if (!c.has_light_trap()) kRecipe.refuse(path + "light_trap: the corners of a light trap cannot all be 0");
  }
}

// Each image's stages default to the recipe's own (read before it: the list order below).
static bool has_images(const Recipe& r) { return !r.images.empty(); }
static json::Value images_json(const Recipe& r) { return write_elements(r.images); }
static void read_images(const json::Value& v, Recipe& r, const Context& c, const std::string& path) {
  if (!v.is_array()) c.refuse("'" + path + "' must be an array");
  r.images.clear();
  for (const auto& e : v.as_array()) {
    const std::string at = path + "[" + std::to_string(r.images.size()) + "]";
    RecipeImage image;
    image.reference = r.reference;
    image.capture = r.capture;
    image.sampling = r.sampling;
    read_members(e, image, c, at);
    if (const json::Value* cap = e.find("capture")) check_light_trap(*cap, image.capture, at + ".capture.");
    r.images.push_back(std::move(image));
  }
}

// `version` is the document's (write_document writes it first, this list the same value again
// in its place; read_document checks it): listed so that a recipe crossing to JS as its JSON keeps it.
TRISTIM_FIELDS_DEFINE(Recipe, member<&Recipe::version>("version", false), member<&Recipe::reference>("reference"),
               member<&Recipe::capture>("capture"), member<&Recipe::sampling>("sampling"),
               member<&Recipe::linearisation>("linearisation"),
               member<&Recipe::surface>("surface"), member<&Recipe::characterisation>("characterisation"),
               member<&Recipe::evaluation>("evaluation"),
               with_shown(Field<Recipe>{"images", images_json, read_images, nullptr, false}, has_images),
               with_shown(member<&Recipe::duplicates>("duplicates", false), has_images));

}  // namespace fields

// ---- the sample flags a recipe may leave out --------------------------------------------------

std::vector<OptionSpec> sample_flag_table() {
  // sample_chart() (chart/layout.cpp) sets these; a saturated patch's mean is biased low in the
  // clipped channel, so it is left out by default (Abed et al. 2013 App. C: unclipped exposures).
  return {number_option("saturated", "Leave out saturated patches", 1, 0, 1,
                        "a pixel of the sample area reached the clip level in some channel: its mean is too low there",
                        "boolean"),
          number_option("dark", "Leave out patches near the noise floor", 0, 0, 1,
                        "a channel's mean is below 0.2 % of its clip level or 3 × the dark frame's noise", "boolean"),
          number_option("nonuniform", "Leave out non-uniform patches", 0, 0, 1,
                        "the sample area's quadrant means differ by > 5 % and > 4 standard errors (glare, a shadow's "
                        "edge, dust, a patch border)",
                        "boolean")};
}

std::string excluding_flags(const SamplingStage& sampling, const std::vector<std::string>& flags) {
  std::string why;
  for (const auto& f : flags)
    if (sampling.exclude_flagged || std::find(sampling.exclude_flags.begin(), sampling.exclude_flags.end(), f) !=
                                        sampling.exclude_flags.end())
      why += (why.empty() ? "" : ", ") + f;
  return why;
}

// ---- completion --------------------------------------------------------------------------

namespace {

// The checks of the stages an image entry has too. `p` prefixes the messages ("recipe: ", or
// "recipe: images[1] ('b.dng'): "); errors of the tables (unknown illuminant, layout) are prefixed
// with it too for an image entry (`image`).
template <class F>
void naming(const std::string& p, bool image, F f) {
  if (!image) return f();
  try {
    f();
  } catch (const Error& e) {
    const std::string what = e.what();
    throw Error(e.code(), what.rfind(p, 0) == 0 ? what : p + (what.rfind("recipe: ", 0) == 0 ? what.substr(8) : what));
  }
}

void complete_stages(ReferenceStage& ref, CaptureStage& cap, SamplingStage& s, const std::string& p, bool image) {
  naming(p, image, [&] {
    // Reference: the illuminant and observer must exist; the chart must be built in or "file".
    illuminant_spd(ref.illuminant);
    ref.observer = observer_name(parse_observer(ref.observer));
    if (ref.chart != "file") {
      bool found = false;
      for (const auto& c : list_charts()) found = found || c.id == ref.chart;
      if (!found) throw Error(ErrorCode::UnknownId, p + "unknown reference chart '" + ref.chart + "'");
    }
    // An alias ("pixel", "channel") is read and written back in the one spelling (dark_mode_id).
    try {
      cap.dark_mode = dark_mode_id(dark_mode_from_id(cap.dark_mode));
    } catch (const Error& e) {
      throw Error(ErrorCode::InvalidArgument, p + "capture.dark_mode: " + e.what());
    }
    if (cap.dark_frames < 0 || cap.saturation < 0 || cap.noise_floor < 0)
      throw Error(ErrorCode::InvalidArgument, p + "capture counts and levels must not be negative");
    chart_layout(s.layout);  // UnknownId / InvalidArgument for a bad layout
    if (!(s.area > 0 && s.area <= 1)) throw Error(ErrorCode::InvalidArgument, p + "sampling.area must be in (0, 1]");
    for (auto& id : s.exclude) id = normalise_patch_id(id);
    for (auto& id : s.missing) id = normalise_patch_id(id);
    // The flags in the table's order, each once; an unknown one refused.
    const std::vector<OptionSpec> table = sample_flag_table();
    std::vector<std::string> flags;
    for (const auto& f : s.exclude_flags)
      if (std::none_of(table.begin(), table.end(), [&f](const OptionSpec& o) { return o.name == f; })) {
        std::string known;
        for (const auto& o : table) known += (known.empty() ? "" : ", ") + o.name;
        throw Error(ErrorCode::UnknownId, p + "sampling.exclude_flags: unknown flag '" + f + "' (known: " + known + ")");
      }
    for (const auto& o : table)
      if (std::find(s.exclude_flags.begin(), s.exclude_flags.end(), o.name) != s.exclude_flags.end()) flags.push_back(o.name);
    s.exclude_flags = flags;
  });
}

void complete_image(RecipeImage& e, size_t k) {
  const std::string p = "recipe: images[" + std::to_string(k) + "] ('" + e.name + "'): ";
  if (e.name.empty()) throw Error(ErrorCode::RecipeInvalid, "recipe: images[" + std::to_string(k) + "] has no name");
  complete_stages(e.reference, e.capture, e.sampling, p, true);
  bool hex = e.sha256.size() == 64;
  for (char c : e.sha256) hex = hex && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
  if (!e.sha256.empty() && !hex) throw Error(ErrorCode::RecipeInvalid, p + "sha256 must be 64 lower-case hex digits");
  const bool index = !e.candidate.empty() && e.candidate.size() < 10 &&
                     std::all_of(e.candidate.begin(), e.candidate.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!e.candidate.empty() && e.candidate != "all" && !index)
    throw Error(ErrorCode::RecipeInvalid, p + "candidate must be \"all\" or a candidate index (0, 1, …)");
  const auto& c = e.sampling.corners;
  const bool corners = std::any_of(c.begin(), c.end(), [](double v) { return v != 0; });
  if (!e.candidate.empty() && corners)
    throw Error(ErrorCode::InvalidArgument, p + "give sampling.corners or a detected candidate, not both");
}

}  // namespace

Recipe complete_recipe(const Recipe& in) {
  Recipe r = in;
  if (r.version != kRecipeVersion)
    throw Error(ErrorCode::RecipeVersion, "recipe version " + std::to_string(r.version) + " is not supported");
  complete_stages(r.reference, r.capture, r.sampling, "recipe: ", false);
  for (size_t k = 0; k < r.images.size(); ++k) complete_image(r.images[k], k);
  if (r.duplicates != kDuplicatesOnce && r.duplicates != kDuplicatesEach)
    throw Error(ErrorCode::InvalidArgument, "recipe: duplicates must be \"once\" or \"each\", not '" + r.duplicates + "'");
  r.linearisation = complete_choice(linearisation_method(r.linearisation.method).info, r.linearisation);
  r.surface = complete_choice(surface_method(r.surface.method).info, r.surface);
  model_info(r.characterisation.model);
  const ObjectiveMethod& obj = objective_method(r.characterisation.objective.method);
  r.characterisation.objective = complete_choice(obj.info, r.characterisation.objective);
  if (!r.characterisation.white_patch.empty())
    r.characterisation.white_patch = normalise_patch_id(r.characterisation.white_patch);
  if (!(r.characterisation.lab_white.minCoeff() > 0))
    throw Error(ErrorCode::InvalidArgument, "recipe: characterisation.lab_white must be positive");
  return r;
}

// ---- JSON --------------------------------------------------------------------------------

json::Value recipe_json(const Recipe& in) { return fields::write_document(complete_recipe(in), kRecipeDocument); }

std::string recipe_to_json(const Recipe& recipe) { return recipe_json(recipe).dump(2) + "\n"; }

Recipe recipe_from_json(const json::Value& o) {
  Recipe r;
  fields::read_document(o, r, kRecipeDocument, kRecipe);
  fields::check_light_trap(o.at("capture"), r.capture, "capture.");
  return complete_recipe(r);
}

Recipe recipe_from_json(const std::string& text) { return recipe_from_json(fields::parse_document(text, kRecipeDocument)); }

// ---- use ---------------------------------------------------------------------------------

namespace {

// Several charts (training_union): a row "1+2:D1" is named by "D1" (the first such row), "1:D1"
// and "2:D1".
bool names_patch(const std::string& row, const std::string& wanted) {
  const auto colon = row.find(':');
  if (colon == std::string::npos) return false;
  const std::string patch = row.substr(colon + 1), charts = "+" + row.substr(0, colon) + "+";
  const auto w = wanted.find(':');
  if (w == std::string::npos) return patch == wanted;
  return patch == wanted.substr(w + 1) && charts.find("+" + wanted.substr(0, w) + "+") != std::string::npos;
}

}  // namespace

FitOptions recipe_fit_options(const Recipe& recipe, const std::vector<std::string>& ids,
                              const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ, int& white_index) {
  const Recipe r = complete_recipe(recipe);
  FitOptions o;
  apply_objective_choice(r.characterisation.objective, o);
  o.white = r.characterisation.lab_white;
  white_index = -1;
  if (!r.characterisation.white_patch.empty()) {
    for (size_t i = 0; i < ids.size(); ++i)
      if (normalise_patch_id(ids[i]) == r.characterisation.white_patch) white_index = static_cast<int>(i);
    for (size_t i = 0; i < ids.size() && white_index < 0 && !r.images.empty(); ++i)
      if (names_patch(ids[i], r.characterisation.white_patch)) white_index = static_cast<int>(i);
    if (white_index < 0)
      throw Error(ErrorCode::UnknownId, "recipe: white patch '" + r.characterisation.white_patch + "' is not in the data");
    o.preserve_white = true;
    o.white_RGB = camera_RGB.row(white_index).transpose();
    o.white_XYZ = reference_XYZ.row(white_index).transpose();
  }
  return o;
}

}  // namespace tristim

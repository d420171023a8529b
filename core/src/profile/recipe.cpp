// Recipe: strict versioned JSON, completion against the method tables, fit options.
#include "tristim/profile/recipe.hpp"

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

TRISTIM_FIELDS(ReferenceStage, member<&ReferenceStage::chart>("chart"), member<&ReferenceStage::data_digest>("data_digest"),
               member<&ReferenceStage::illuminant>("illuminant"), member<&ReferenceStage::observer>("observer"));

static bool has_light_trap(const CaptureStage& c) { return c.has_light_trap(); }
TRISTIM_FIELDS(CaptureStage, member<&CaptureStage::dark_frames>("dark_frames"), member<&CaptureStage::dark_mode>("dark_mode"),
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
TRISTIM_FIELDS(LayoutOptions, member<&LayoutOptions::chart>("chart"), member<&LayoutOptions::rows>("rows"),
               member<&LayoutOptions::columns>("columns"), Field<LayoutOptions>{"margins", margins_json, read_margins},
               member<&LayoutOptions::gap>("gap"));

TRISTIM_FIELDS(SamplingStage, member<&SamplingStage::layout>("layout"), member<&SamplingStage::corners>("corners"),
               member<&SamplingStage::area>("area"), member<&SamplingStage::exclude>("exclude"),
               member<&SamplingStage::exclude_flagged>("exclude_flagged"));

TRISTIM_FIELDS(CharacterisationStage, member<&CharacterisationStage::model>("model"),
               member<&CharacterisationStage::objective>("objective"),
               member<&CharacterisationStage::white_patch>("white_patch"),
               member<&CharacterisationStage::lab_white>("lab_white"));

TRISTIM_FIELDS(EvaluationStage, member<&EvaluationStage::leave_one_out>("leave_one_out"),
               member<&EvaluationStage::held_out_digest>("held_out_digest"));

TRISTIM_FIELDS(Recipe, member<&Recipe::reference>("reference"), member<&Recipe::capture>("capture"),
               member<&Recipe::sampling>("sampling"), member<&Recipe::linearisation>("linearisation"),
               member<&Recipe::surface>("surface"), member<&Recipe::characterisation>("characterisation"),
               member<&Recipe::evaluation>("evaluation"));

}  // namespace fields

// ---- completion --------------------------------------------------------------------------

Recipe complete_recipe(const Recipe& in) {
  Recipe r = in;
  if (r.version != kRecipeVersion)
    throw Error(ErrorCode::RecipeVersion, "recipe version " + std::to_string(r.version) + " is not supported");
  // Reference: the illuminant and observer must exist; the chart must be built in or "file".
  illuminant_spd(r.reference.illuminant);
  r.reference.observer = observer_name(parse_observer(r.reference.observer));
  if (r.reference.chart != "file") {
    bool found = false;
    for (const auto& c : list_charts()) found = found || c.id == r.reference.chart;
    if (!found) throw Error(ErrorCode::UnknownId, "recipe: unknown reference chart '" + r.reference.chart + "'");
  }
  // An alias ("pixel", "channel") is read and written back in the one spelling (dark_mode_id).
  try {
    r.capture.dark_mode = dark_mode_id(dark_mode_from_id(r.capture.dark_mode));
  } catch (const Error& e) {
    throw Error(ErrorCode::InvalidArgument, std::string("recipe: capture.dark_mode: ") + e.what());
  }
  if (r.capture.dark_frames < 0 || r.capture.saturation < 0 || r.capture.noise_floor < 0)
    throw Error(ErrorCode::InvalidArgument, "recipe: capture counts and levels must not be negative");
  chart_layout(r.sampling.layout);  // UnknownId / InvalidArgument for a bad layout
  if (!(r.sampling.area > 0 && r.sampling.area <= 1))
    throw Error(ErrorCode::InvalidArgument, "recipe: sampling.area must be in (0, 1]");
  for (auto& id : r.sampling.exclude) id = normalise_patch_id(id);
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
  const json::Value& cap = o.at("capture");
  if (cap.find("light_trap") || cap.find("flare")) {  // optional, but the two together
    if (!cap.find("light_trap") || !cap.find("flare")) kRecipe.refuse("capture.light_trap and capture.flare go together");
    if (!r.capture.has_light_trap()) kRecipe.refuse("capture.light_trap: the corners of a light trap cannot all be 0");
  }
  return complete_recipe(r);
}

Recipe recipe_from_json(const std::string& text) { return recipe_from_json(fields::parse_document(text, kRecipeDocument)); }

// ---- use ---------------------------------------------------------------------------------

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
    if (white_index < 0)
      throw Error(ErrorCode::UnknownId, "recipe: white patch '" + r.characterisation.white_patch + "' is not in the data");
    o.preserve_white = true;
    o.white_RGB = camera_RGB.row(white_index).transpose();
    o.white_XYZ = reference_XYZ.row(white_index).transpose();
  }
  return o;
}

}  // namespace tristim

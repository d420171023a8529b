// Recipe: strict versioned JSON, completion against the method tables, fit options.
#include "tristim/profile/recipe.hpp"

#include <cmath>
#include <set>

#include "tristim/capture/calibration.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

namespace {

// ---- strict reading: every member must be known, of the right type -------------------------

[[noreturn]] void invalid(const std::string& what) { throw Error(ErrorCode::RecipeInvalid, "recipe: " + what); }

/// An object's members checked against `known` (unknown → RecipeInvalid naming the field).
const json::Value& object_at(const json::Value& parent, const std::string& key, const std::string& path,
                             std::initializer_list<const char*> known) {
  const json::Value* v = parent.find(key);
  if (!v) invalid("missing field '" + path + "'");
  if (!v->is_object()) invalid("'" + path + "' must be an object");
  for (const auto& [name, value] : v->members()) {
    bool ok = false;
    for (const char* k : known) ok = ok || name == k;
    if (!ok) invalid("unknown field '" + path + "." + name + "'");
  }
  return *v;
}

const json::Value& member(const json::Value& o, const std::string& key, const std::string& path) {
  const json::Value* v = o.find(key);
  if (!v) invalid("missing field '" + path + "." + key + "'");
  return *v;
}

std::string text(const json::Value& o, const std::string& key, const std::string& path) {
  const json::Value& v = member(o, key, path);
  if (!v.is_string()) invalid("'" + path + "." + key + "' must be a string");
  return v.as_string();
}

double number(const json::Value& o, const std::string& key, const std::string& path) {
  const json::Value& v = member(o, key, path);
  if (!v.is_number() || !std::isfinite(v.as_number())) invalid("'" + path + "." + key + "' must be a finite number");
  return v.as_number();
}

int integer(const json::Value& o, const std::string& key, const std::string& path) {
  const double d = number(o, key, path);
  if (d != std::floor(d) || std::fabs(d) > 1e9) invalid("'" + path + "." + key + "' must be an integer");
  return static_cast<int>(d);
}

bool boolean(const json::Value& o, const std::string& key, const std::string& path) {
  const json::Value& v = member(o, key, path);
  if (!v.is_bool()) invalid("'" + path + "." + key + "' must be true or false");
  return v.as_bool();
}

std::vector<double> numbers(const json::Value& o, const std::string& key, const std::string& path, size_t n) {
  const json::Value& v = member(o, key, path);
  if (!v.is_array()) invalid("'" + path + "." + key + "' must be an array");
  if (v.size() != n) invalid("'" + path + "." + key + "' must have " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (const auto& e : v.as_array()) {
    if (!e.is_number() || !std::isfinite(e.as_number())) invalid("'" + path + "." + key + "' must hold finite numbers");
    out.push_back(e.as_number());
  }
  return out;
}

std::vector<std::string> strings(const json::Value& o, const std::string& key, const std::string& path) {
  const json::Value& v = member(o, key, path);
  if (!v.is_array()) invalid("'" + path + "." + key + "' must be an array");
  std::vector<std::string> out;
  for (const auto& e : v.as_array()) {
    if (!e.is_string()) invalid("'" + path + "." + key + "' must hold strings");
    out.push_back(e.as_string());
  }
  return out;
}

MethodChoice read_choice(const json::Value& parent, const std::string& key, const std::string& path) {
  const json::Value& o = object_at(parent, key, path, {"method", "parameters", "settings"});
  MethodChoice c;
  c.method = text(o, "method", path);
  if (const json::Value* p = o.find("parameters")) {
    if (!p->is_object()) invalid("'" + path + ".parameters' must be an object");
    for (const auto& [name, v] : p->members()) {
      if (v.is_bool()) c.parameters[name] = v.as_bool() ? 1 : 0;
      else if (v.is_number() && std::isfinite(v.as_number())) c.parameters[name] = v.as_number();
      else invalid("'" + path + ".parameters." + name + "' must be a finite number");
    }
  }
  if (const json::Value* s = o.find("settings")) {
    if (!s->is_object()) invalid("'" + path + ".settings' must be an object");
    for (const auto& [name, v] : s->members()) {
      if (!v.is_string()) invalid("'" + path + ".settings." + name + "' must be a string");
      c.settings[name] = v.as_string();
    }
  }
  return c;
}

json::Value choice_json(const MethodChoice& c) {
  json::Value o = json::Value::object();
  o.set("method", c.method);
  json::Value p = json::Value::object();
  for (const auto& [name, v] : c.parameters) p.set(name, v);
  o.set("parameters", p);
  json::Value s = json::Value::object();
  for (const auto& [name, v] : c.settings) s.set(name, v);
  o.set("settings", s);
  return o;
}

json::Value string_array(const std::vector<std::string>& v) {
  json::Value a = json::Value::array();
  for (const auto& s : v) a.push(s);
  return a;
}

}  // namespace

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

json::Value recipe_json(const Recipe& in) {
  const Recipe r = complete_recipe(in);
  json::Value o = json::Value::object();
  o.set("format", "tristim-recipe");
  o.set("version", r.version);

  json::Value ref = json::Value::object();
  ref.set("chart", r.reference.chart);
  ref.set("data_digest", r.reference.data_digest);
  ref.set("illuminant", r.reference.illuminant);
  ref.set("observer", r.reference.observer);
  o.set("reference", ref);

  json::Value cap = json::Value::object();
  cap.set("dark_frames", r.capture.dark_frames);
  cap.set("dark_mode", r.capture.dark_mode);
  cap.set("flat_field", r.capture.flat_field);
  cap.set("falloff", r.capture.falloff);
  cap.set("saturation", r.capture.saturation);
  cap.set("noise_floor", r.capture.noise_floor);
  if (r.capture.has_light_trap()) {
    cap.set("light_trap", json::Value(std::vector<double>(r.capture.light_trap.begin(), r.capture.light_trap.end())));
    cap.set("flare", json::Value(std::vector<double>(r.capture.flare.begin(), r.capture.flare.end())));
  }
  o.set("capture", cap);

  json::Value lay = json::Value::object();
  const LayoutOptions& L = r.sampling.layout;
  lay.set("chart", L.chart);
  lay.set("rows", L.rows);
  lay.set("columns", L.columns);
  lay.set("margins", json::Value(std::vector<double>{L.margin_left, L.margin_top, L.margin_right, L.margin_bottom}));
  lay.set("gap", L.gap);
  json::Value smp = json::Value::object();
  smp.set("layout", lay);
  smp.set("corners", json::Value(std::vector<double>(r.sampling.corners.begin(), r.sampling.corners.end())));
  smp.set("area", r.sampling.area);
  smp.set("exclude", string_array(r.sampling.exclude));
  smp.set("exclude_flagged", r.sampling.exclude_flagged);
  o.set("sampling", smp);

  o.set("linearisation", choice_json(r.linearisation));
  o.set("surface", choice_json(r.surface));

  json::Value ch = json::Value::object();
  ch.set("model", r.characterisation.model);
  ch.set("objective", choice_json(r.characterisation.objective));
  ch.set("white_patch", r.characterisation.white_patch);
  const Vec3& w = r.characterisation.lab_white;
  ch.set("lab_white", json::Value(std::vector<double>{w[0], w[1], w[2]}));
  o.set("characterisation", ch);

  json::Value ev = json::Value::object();
  ev.set("leave_one_out", r.evaluation.leave_one_out);
  ev.set("held_out_digest", r.evaluation.held_out_digest);
  o.set("evaluation", ev);
  return o;
}

std::string recipe_to_json(const Recipe& recipe) { return recipe_json(recipe).dump(2) + "\n"; }

Recipe recipe_from_json(const json::Value& o) {
  if (!o.is_object()) invalid("a recipe must be a JSON object");
  const json::Value* fmt = o.find("format");
  if (!fmt || !fmt->is_string() || fmt->as_string() != "tristim-recipe")
    invalid("not a tristim recipe (\"format\" must be \"tristim-recipe\")");
  const json::Value* ver = o.find("version");
  if (!ver) invalid("missing field 'version'");
  if (!ver->is_number() || ver->as_number() != kRecipeVersion)
    throw Error(ErrorCode::RecipeVersion,
                "recipe version " + (ver->is_number() ? json::number_text(ver->as_number()) : std::string("?")) +
                    " is not supported (this tristim reads version " + std::to_string(kRecipeVersion) + ")");
  static const std::set<std::string> top = {"format", "version", "reference", "capture", "sampling",
                                            "linearisation", "surface", "characterisation", "evaluation"};
  for (const auto& [name, v] : o.members())
    if (!top.count(name)) invalid("unknown field '" + name + "'");

  Recipe r;
  const json::Value& ref = object_at(o, "reference", "reference", {"chart", "data_digest", "illuminant", "observer"});
  r.reference.chart = text(ref, "chart", "reference");
  r.reference.data_digest = text(ref, "data_digest", "reference");
  r.reference.illuminant = text(ref, "illuminant", "reference");
  r.reference.observer = text(ref, "observer", "reference");

  const json::Value& cap = object_at(o, "capture", "capture",
                                     {"dark_frames", "dark_mode", "flat_field", "falloff", "saturation", "noise_floor",
                                      "light_trap", "flare"});
  r.capture.dark_frames = integer(cap, "dark_frames", "capture");
  r.capture.dark_mode = text(cap, "dark_mode", "capture");
  r.capture.flat_field = boolean(cap, "flat_field", "capture");
  r.capture.falloff = boolean(cap, "falloff", "capture");
  r.capture.saturation = number(cap, "saturation", "capture");
  r.capture.noise_floor = number(cap, "noise_floor", "capture");
  if (cap.find("light_trap") || cap.find("flare")) {  // optional: only recipes with a light trap have them
    const auto t = numbers(cap, "light_trap", "capture", 8);
    std::copy(t.begin(), t.end(), r.capture.light_trap.begin());
    const auto f = numbers(cap, "flare", "capture", 3);
    std::copy(f.begin(), f.end(), r.capture.flare.begin());
    if (!r.capture.has_light_trap()) invalid("capture.light_trap: the corners of a light trap cannot all be 0");
  }

  const json::Value& smp = object_at(o, "sampling", "sampling", {"layout", "corners", "area", "exclude", "exclude_flagged"});
  const json::Value& lay = object_at(smp, "layout", "sampling.layout", {"chart", "rows", "columns", "margins", "gap"});
  r.sampling.layout.chart = text(lay, "chart", "sampling.layout");
  r.sampling.layout.rows = integer(lay, "rows", "sampling.layout");
  r.sampling.layout.columns = integer(lay, "columns", "sampling.layout");
  const auto m = numbers(lay, "margins", "sampling.layout", 4);
  r.sampling.layout.margin_left = m[0];
  r.sampling.layout.margin_top = m[1];
  r.sampling.layout.margin_right = m[2];
  r.sampling.layout.margin_bottom = m[3];
  r.sampling.layout.gap = number(lay, "gap", "sampling.layout");
  const auto c = numbers(smp, "corners", "sampling", 8);
  std::copy(c.begin(), c.end(), r.sampling.corners.begin());
  r.sampling.area = number(smp, "area", "sampling");
  r.sampling.exclude = strings(smp, "exclude", "sampling");
  r.sampling.exclude_flagged = boolean(smp, "exclude_flagged", "sampling");

  r.linearisation = read_choice(o, "linearisation", "linearisation");
  r.surface = read_choice(o, "surface", "surface");

  const json::Value& ch = object_at(o, "characterisation", "characterisation", {"model", "objective", "white_patch", "lab_white"});
  r.characterisation.model = text(ch, "model", "characterisation");
  r.characterisation.objective = read_choice(ch, "objective", "characterisation.objective");
  r.characterisation.white_patch = text(ch, "white_patch", "characterisation");
  const auto w = numbers(ch, "lab_white", "characterisation", 3);
  r.characterisation.lab_white = Vec3(w[0], w[1], w[2]);

  const json::Value& ev = object_at(o, "evaluation", "evaluation", {"leave_one_out", "held_out_digest"});
  r.evaluation.leave_one_out = boolean(ev, "leave_one_out", "evaluation");
  r.evaluation.held_out_digest = text(ev, "held_out_digest", "evaluation");
  return complete_recipe(r);
}

Recipe recipe_from_json(const std::string& text) {
  json::Value v;
  try {
    v = json::parse(text);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::LimitExceeded)  // a stated limit (io/limits.hpp) keeps its code
      throw Error(ErrorCode::LimitExceeded, std::string("recipe: ") + e.what());
    invalid(std::string("not valid JSON: ") + e.what());
  }
  return recipe_from_json(v);
}

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

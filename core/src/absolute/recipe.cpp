// AbsoluteRecipe: rows, completion against the tables, strict versioned JSON (rules in
// tristim/absolute/recipe.hpp).
#include "tristim/absolute/recipe.hpp"

#include <cmath>
#include <cstdio>

#include "tristim/absolute/fusion.hpp"
#include "tristim/absolute/stimuli_file.hpp"
#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

// The zone parameter: Z_c = [1/w, (w−1)/w] is empty for w ≤ 2 (section 3.1); above 1e6 Z_u and
// Z_o are narrower than one DN of any sensor.
constexpr double kZoneWidthMin = 2, kZoneWidthMax = 1e6;

std::string text_of(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string set_of(const std::string& set, const Vec3& XYZ, const std::string& where) {
  if (set.empty()) return equal_tristimulus(XYZ) ? "luminance" : "colour";
  if (set == "luminance" || set == "oecf") return "luminance";
  if (set == "colour" || set == "color") return "colour";
  throw Error(ErrorCode::InvalidArgument, where + ": set is luminance or colour, not '" + set + "'");
}

// ---- strict reading: object members checked against the known ones, types by the accessors ----

const json::Value& object_at(const json::Value& parent, const std::string& key, const std::string& path,
                             std::initializer_list<const char*> known) {
  const json::Value& v = parent.at(key);
  if (!v.is_object()) throw Error(ErrorCode::RecipeInvalid, "absolute recipe: '" + path + "' must be an object");
  json::reject_unknown(v, known, "absolute recipe: '" + path + "'", ErrorCode::RecipeInvalid);
  return v;
}

std::vector<double> fixed_numbers(const json::Value& o, const std::string& key, const std::string& path, size_t n) {
  const auto v = o.at(key).as_numbers(path + "." + key);
  if (v.size() != n)
    throw Error(ErrorCode::RecipeInvalid, "absolute recipe: '" + path + "." + key + "' must have " + std::to_string(n) + " numbers");
  return v;
}

Vec3 vec3_at(const json::Value& o, const std::string& key, const std::string& path) {
  const auto v = fixed_numbers(o, key, path, 3);
  return Vec3(v[0], v[1], v[2]);
}

std::vector<std::string> strings_at(const json::Value& o, const std::string& key, const std::string& path) {
  std::vector<std::string> out;
  for (const auto& e : o.at(key).as_array(path + "." + key)) out.push_back(e.as_string(path + "." + key + " element"));
  return out;
}

json::Value vec3_json(const Vec3& v) { return json::Value(std::vector<double>{v[0], v[1], v[2]}); }

json::Value strings_json(const std::vector<std::string>& v) {
  json::Value a = json::Value::array();
  for (const auto& s : v) a.push(s);
  return a;
}

json::Value stimulus_json(const AbsoluteStimulus& s) {
  json::Value o = json::Value::object();
  o.set("id", s.id);
  o.set("set", s.set);
  o.set("exposure", json::Value(std::vector<double>{s.exposure.exposure_s, s.exposure.f_number, s.exposure.iso}));
  o.set("file", s.file);
  o.set("region", json::Value(std::vector<double>{double(s.x), double(s.y), double(s.w), double(s.h)}));
  o.set("RGB", vec3_json(s.RGB));
  o.set("falloff", s.falloff);
  o.set("XYZ", vec3_json(s.XYZ));
  return o;
}

AbsoluteStimulus stimulus_from(const json::Value& o, const std::string& path) {
  if (!o.is_object()) throw Error(ErrorCode::RecipeInvalid, "absolute recipe: '" + path + "' must be an object");
  json::reject_unknown(o, {"id", "set", "exposure", "file", "region", "RGB", "falloff", "XYZ"}, "absolute recipe: '" + path + "'",
                       ErrorCode::RecipeInvalid);
  AbsoluteStimulus s;
  s.id = o.at("id").as_string(path + ".id");
  s.set = o.at("set").as_string(path + ".set");
  const auto e = fixed_numbers(o, "exposure", path, 3);
  s.exposure = {e[0], e[1], e[2]};
  s.file = o.at("file").as_string(path + ".file");
  const auto& r = o.at("region").as_array(path + ".region");
  if (r.size() != 4) throw Error(ErrorCode::RecipeInvalid, "absolute recipe: '" + path + ".region' must have 4 numbers");
  s.x = r[0].as_int(path + ".region", -limits::kMaxJsonInt, limits::kMaxJsonInt);
  s.y = r[1].as_int(path + ".region", -limits::kMaxJsonInt, limits::kMaxJsonInt);
  s.w = r[2].as_int(path + ".region", 0, limits::kMaxJsonInt);
  s.h = r[3].as_int(path + ".region", 0, limits::kMaxJsonInt);
  s.RGB = vec3_at(o, "RGB", path);
  s.falloff = o.at("falloff").as_number(path + ".falloff");
  s.XYZ = vec3_at(o, "XYZ", path);
  return s;
}

}  // namespace

// ---- rows --------------------------------------------------------------------------------

std::vector<AbsoluteStimulus> read_absolute_stimuli(std::string_view text, const std::string& source) {
  std::vector<AbsoluteStimulus> out;
  for (const auto& r : read_stimuli_csv(text, source.empty() ? "stimuli" : source)) {
    AbsoluteStimulus s;
    s.id = r.stimulus.id;
    s.set = r.stimulus.luminance_set ? "luminance" : "colour";
    s.exposure = r.stimulus.exposure;
    s.RGB = r.stimulus.raw_RGB;
    s.falloff = r.stimulus.falloff;
    s.file = r.file;
    s.x = r.x, s.y = r.y, s.w = r.w, s.h = r.h;
    s.XYZ = r.stimulus.XYZ;
    s.line = r.line;
    out.push_back(s);
  }
  return out;
}

std::string absolute_stimuli_to_csv(const std::vector<AbsoluteStimulus>& rows) {
  std::string out = "id,set,exposure_s,f_number,iso,file,x,y,w,h,R,G,B,falloff,X,Y,Z\n";
  for (const auto& s : rows) {
    out += s.id + "," + s.set + "," + text_of(s.exposure.exposure_s) + "," + text_of(s.exposure.f_number) + "," +
           text_of(s.exposure.iso) + ",";
    if (s.region())
      out += s.file + "," + std::to_string(s.x) + "," + std::to_string(s.y) + "," + std::to_string(s.w) + "," +
             std::to_string(s.h) + ",,,,";
    else
      out += ",,,,," + text_of(s.RGB[0]) + "," + text_of(s.RGB[1]) + "," + text_of(s.RGB[2]) + "," + text_of(s.falloff);
    out += "," + text_of(s.XYZ[0]) + "," + text_of(s.XYZ[1]) + "," + text_of(s.XYZ[2]) + "\n";
  }
  return out;
}

std::string stimulus_where(const AbsoluteStimulus& s) {
  return "stimulus '" + s.id + "'" + (s.line > 0 ? " (line " + std::to_string(s.line) + ")" : "");
}

// ---- the table and completion ------------------------------------------------------------

std::vector<OptionSpec> absolute_option_table() {
  auto number = [](const char* name, const char* label, double def, double lo, double hi, const char* what) {
    OptionSpec o;
    o.name = name, o.type = "number", o.label = label, o.default_number = def, o.min = lo, o.max = hi, o.description = what;
    return o;
  };
  auto choice = [](const char* name, const char* label, const char* def, std::vector<std::string> choices, const char* what) {
    OptionSpec o;
    o.name = name, o.type = "choice", o.label = label, o.default_text = def, o.choices = std::move(choices), o.description = what;
    return o;
  };
  return {
      choice("transform", "Colour transform", "T1", {"T1", "To", "T2R"},
             "the polynomial T of eq (4): T1 linear (eq 13), To with an offset (eq 14), T2R root-polynomial (eq 15)"),
      choice("fusion", "Exposure fusion", "weighted", {"weighted", "recursive"},
             "weighted: every reliable exposure, by reliability x t/N^2; recursive: Algorithm 1"),
      number("w", "Zone parameter w", 10, kZoneWidthMin, kZoneWidthMax,
             "section 3.1: Z_c = [1/w, (w-1)/w] of the (S - n) interval is the reliable zone; more than 2"),
      number("noise_floor", "Noise floor n (DN)", 0, 0, 1e9, "eq (7), when no lens-cap frames are given"),
      number("saturation", "Saturation S (DN)", 0, 0, 1e9, "eq (7); 0: measured from the frames (where the body clips)"),
  };
}

AbsoluteRecipe complete_absolute_recipe(const AbsoluteRecipe& in) {
  AbsoluteRecipe r = in;
  if (r.version != kAbsoluteRecipeVersion)
    throw Error(ErrorCode::RecipeVersion, "absolute recipe version " + std::to_string(r.version) + " is not supported");
  AbsoluteOptions& o = r.options;
  if (o.transform != "T1" && o.transform != "To" && o.transform != "T2R")
    throw Error(ErrorCode::UnknownId, "absolute recipe: transform '" + o.transform + "' (expected T1, To, T2R)");
  o.fusion = fusion_mode_id(fusion_mode_from_id(o.fusion));
  if (!(o.w > kZoneWidthMin && o.w <= kZoneWidthMax))
    throw Error(ErrorCode::InvalidArgument, "the zone parameter w must be more than 2 and at most 1e6, got " + text_of(o.w));
  if (!(o.noise_floor >= 0 && o.noise_floor <= 1e9) || !(o.saturation >= 0 && o.saturation <= 1e9))
    throw Error(ErrorCode::InvalidArgument, "the noise floor and the saturation level must be in 0 … 1e9 DN");
  for (auto& s : r.inputs.stimuli) {
    const std::string where = stimulus_where(s);
    s.set = set_of(s.set, s.XYZ, where);
    if (!s.XYZ.allFinite() || !s.RGB.allFinite() || !std::isfinite(s.falloff))
      throw Error(ErrorCode::NonFinite, where + ": X, Y, Z, R, G, B and the fall-off must be finite");
    if (s.region()) {
      if (s.w <= 0 || s.h <= 0) throw Error(ErrorCode::InvalidArgument, where + ": the region needs a positive width and height");
    } else if (!(s.exposure.exposure_s > 0) || !(s.exposure.f_number > 0)) {
      throw Error(ErrorCode::MissingMetadata, where + ": a per-patch stimulus needs exposure_s and f_number");
    }
  }
  AbsoluteSensitivities& a = r.inputs.sensitivities;
  if (a.choice == "none") {
    a.camera.clear(), a.source.clear(), a.ssf = {};
  } else if (a.choice == "camera") {
    camera_ssf(a.camera);  // UnknownId for a camera that is not built in
    a.source.clear(), a.ssf = {};
  } else if (a.choice == "given") {
    if (a.ssf.size() != 3) throw Error(ErrorCode::InvalidArgument, "given sensitivities need three curves (R, G, B)");
    channel_areas(a.ssf);  // InvalidArgument for a curve without a positive area
    a.ssf.names = {"R", "G", "B"};  // what the JSON keeps: the curves by channel, areas by trapezoids
    a.ssf.linear = false;
    a.camera.clear();
    if (a.source.empty()) a.source = "given";
  } else {
    throw Error(ErrorCode::InvalidArgument, "sensitivities: choice is none, camera or given, not '" + a.choice + "'");
  }
  return r;
}

// ---- JSON --------------------------------------------------------------------------------

json::Value absolute_recipe_json(const AbsoluteRecipe& in) {
  const AbsoluteRecipe r = complete_absolute_recipe(in);
  json::Value o = json::Value::object();
  o.set("format", "tristim-absolute-recipe");
  o.set("version", r.version);
  json::Value inputs = json::Value::object();
  json::Value rows = json::Value::array();
  for (const auto& s : r.inputs.stimuli) rows.push(stimulus_json(s));
  inputs.set("stimuli", rows);
  inputs.set("bracket", strings_json(r.inputs.bracket));
  inputs.set("lens_cap", strings_json(r.inputs.lens_cap));
  inputs.set("flat", r.inputs.flat);
  const AbsoluteSensitivities& a = r.inputs.sensitivities;
  json::Value sens = json::Value::object();
  sens.set("choice", a.choice);
  sens.set("camera", a.camera);
  sens.set("source", a.source);
  sens.set("wavelengths", json::Value(a.ssf.wavelengths));
  for (size_t c = 0; c < 3; ++c) sens.set(std::string(1, "RGB"[c]), json::Value(c < a.ssf.size() ? a.ssf.values[c] : std::vector<double>{}));
  inputs.set("sensitivities", sens);
  o.set("inputs", inputs);
  json::Value opt = json::Value::object();
  opt.set("transform", r.options.transform);
  opt.set("fusion", r.options.fusion);
  opt.set("w", r.options.w);
  opt.set("noise_floor", r.options.noise_floor);
  opt.set("saturation", r.options.saturation);
  o.set("options", opt);
  return o;
}

std::string absolute_recipe_to_json(const AbsoluteRecipe& recipe) { return absolute_recipe_json(recipe).dump(2) + "\n"; }

AbsoluteRecipe absolute_recipe_from_json(const json::Value& o) {
  if (!o.is_object()) throw Error(ErrorCode::RecipeInvalid, "an absolute recipe must be a JSON object");
  const json::Value* fmt = o.find("format");
  if (!fmt || !fmt->is_string() || fmt->as_string() != "tristim-absolute-recipe")
    throw Error(ErrorCode::RecipeInvalid, "not a tristim absolute recipe (\"format\" must be \"tristim-absolute-recipe\")");
  const json::Value* ver = o.find("version");
  if (!ver || !ver->is_number()) throw Error(ErrorCode::RecipeInvalid, "absolute recipe: missing field 'version'");
  if (ver->as_number() != kAbsoluteRecipeVersion)
    throw Error(ErrorCode::RecipeVersion, "absolute recipe version " + json::number_text(ver->as_number()) +
                                              " is not supported (this tristim reads version " +
                                              std::to_string(kAbsoluteRecipeVersion) + ")");
  AbsoluteRecipe r;
  try {
    json::reject_unknown(o, {"format", "version", "inputs", "options"}, "absolute recipe", ErrorCode::RecipeInvalid);
    const json::Value& in = object_at(o, "inputs", "inputs", {"stimuli", "bracket", "lens_cap", "flat", "sensitivities"});
    const auto& rows = in.at("stimuli").as_array("inputs.stimuli");
    for (size_t i = 0; i < rows.size(); ++i)
      r.inputs.stimuli.push_back(stimulus_from(rows[i], "inputs.stimuli[" + std::to_string(i) + "]"));
    r.inputs.bracket = strings_at(in, "bracket", "inputs");
    r.inputs.lens_cap = strings_at(in, "lens_cap", "inputs");
    r.inputs.flat = in.at("flat").as_string("inputs.flat");
    const json::Value& sens =
        object_at(in, "sensitivities", "inputs.sensitivities", {"choice", "camera", "source", "wavelengths", "R", "G", "B"});
    AbsoluteSensitivities& a = r.inputs.sensitivities;
    a.choice = sens.at("choice").as_string("inputs.sensitivities.choice");
    a.camera = sens.at("camera").as_string("inputs.sensitivities.camera");
    a.source = sens.at("source").as_string("inputs.sensitivities.source");
    if (a.choice == "given") {
      a.ssf.wavelengths = sens.at("wavelengths").as_numbers("inputs.sensitivities.wavelengths");
      for (const char* c : {"R", "G", "B"}) {
        a.ssf.names.push_back(c);
        a.ssf.values.push_back(sens.at(c).as_numbers(std::string("inputs.sensitivities.") + c));
        if (a.ssf.values.back().size() != a.ssf.wavelengths.size())
          throw Error(ErrorCode::RecipeInvalid, std::string("absolute recipe: inputs.sensitivities.") + c +
                                                    " must have one value per wavelength");
      }
    }
    const json::Value& opt = object_at(o, "options", "options", {"transform", "fusion", "w", "noise_floor", "saturation"});
    r.options.transform = opt.at("transform").as_string("options.transform");
    r.options.fusion = opt.at("fusion").as_string("options.fusion");
    r.options.w = opt.at("w").as_number("options.w");
    r.options.noise_floor = opt.at("noise_floor").as_number("options.noise_floor");
    r.options.saturation = opt.at("saturation").as_number("options.saturation");
  } catch (const Error& e) {
    // The JSON accessors name the field with ProfileInvalid: a recipe says RecipeInvalid.
    if (e.code() != ErrorCode::ProfileInvalid) throw;
    throw Error(ErrorCode::RecipeInvalid, std::string("absolute recipe: ") + e.what());
  }
  return complete_absolute_recipe(r);
}

AbsoluteRecipe absolute_recipe_from_json(const std::string& text) {
  json::Value v;
  try {
    v = json::parse(text);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::LimitExceeded) throw Error(ErrorCode::LimitExceeded, std::string("absolute recipe: ") + e.what());
    throw Error(ErrorCode::RecipeInvalid, std::string("absolute recipe: not valid JSON: ") + e.what());
  }
  return absolute_recipe_from_json(v);
}

}  // namespace tristim

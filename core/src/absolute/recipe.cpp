// AbsoluteRecipe: rows, completion against the tables, strict versioned JSON (rules in
// tristim/absolute/recipe.hpp).
#include "tristim/absolute/recipe.hpp"

#include <cmath>
#include <cstdio>

#include "tristim/absolute/fusion.hpp"
#include "../citations.hpp"
#include "tristim/absolute/stimuli_file.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "fields.hpp"

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

const fields::Context kAbsoluteRecipe{ErrorCode::RecipeInvalid, "absolute recipe: "};
const fields::Document kDocument{"tristim-absolute-recipe", kAbsoluteRecipeVersion, "absolute recipe",
                                 ErrorCode::RecipeInvalid, ErrorCode::RecipeVersion};

}  // namespace

// ---- the field lists: the JSON writer and the strict reader come from these ------------------

namespace fields {

static json::Value region_json(const AbsoluteStimulus& s) {
  return json::Value(std::vector<double>{double(s.x), double(s.y), double(s.w), double(s.h)});
}
static void read_region(const json::Value& v, AbsoluteStimulus& s, const Context& c, const std::string& path) {
  if (!v.is_array() || v.size() != 4) c.refuse("'" + path + "' must have 4 numbers");
  const auto& r = v.as_array();
  try {
    s.x = r[0].as_int(path, -limits::kMaxJsonInt, limits::kMaxJsonInt);
    s.y = r[1].as_int(path, -limits::kMaxJsonInt, limits::kMaxJsonInt);
    s.w = r[2].as_int(path, 0, limits::kMaxJsonInt);
    s.h = r[3].as_int(path, 0, limits::kMaxJsonInt);
  } catch (const Error& e) {
    c.refuse(e.what());
  }
}
TRISTIM_FIELDS_DEFINE(AbsoluteStimulus, member<&AbsoluteStimulus::id>("id"), member<&AbsoluteStimulus::set>("set"),
               member<&AbsoluteStimulus::exposure>("exposure"), member<&AbsoluteStimulus::file>("file"),
               Field<AbsoluteStimulus>{"region", region_json, read_region}, member<&AbsoluteStimulus::RGB>("RGB"),
               member<&AbsoluteStimulus::falloff>("falloff"), member<&AbsoluteStimulus::XYZ>("XYZ"));

// The given curves are kept as SpectralData; the JSON has them by channel (R, G, B), one value per
// wavelength. Written always (empty unless "given"), read when present (completion keeps them
// only for "given").
static json::Value wavelengths_json(const AbsoluteSensitivities& a) { return json::Value(a.ssf.wavelengths); }
static void read_wavelengths(const json::Value& v, AbsoluteSensitivities& a, const Context& c, const std::string& path) {
  read(v, a.ssf.wavelengths, c, path);
}
template <size_t C>
json::Value channel_json(const AbsoluteSensitivities& a) {
  return json::Value(C < a.ssf.size() ? a.ssf.values[C] : std::vector<double>{});
}
template <size_t C>
void read_channel(const json::Value& v, AbsoluteSensitivities& a, const Context& c, const std::string& path) {
  a.ssf.names = {"R", "G", "B"};
  a.ssf.values.resize(3);
  read(v, a.ssf.values[C], c, path);
}
TRISTIM_FIELDS_DEFINE(AbsoluteSensitivities, member<&AbsoluteSensitivities::choice>("choice"),
               member<&AbsoluteSensitivities::camera>("camera"), member<&AbsoluteSensitivities::source>("source"),
               Field<AbsoluteSensitivities>{"wavelengths", wavelengths_json, read_wavelengths, nullptr, false},
               Field<AbsoluteSensitivities>{"R", channel_json<0>, read_channel<0>, nullptr, false},
               Field<AbsoluteSensitivities>{"G", channel_json<1>, read_channel<1>, nullptr, false},
               Field<AbsoluteSensitivities>{"B", channel_json<2>, read_channel<2>, nullptr, false});

TRISTIM_FIELDS_DEFINE(AbsoluteInputs, member<&AbsoluteInputs::stimuli>("stimuli"), member<&AbsoluteInputs::bracket>("bracket"),
               member<&AbsoluteInputs::lens_cap>("lens_cap"), member<&AbsoluteInputs::flat>("flat"),
               member<&AbsoluteInputs::sensitivities>("sensitivities"));

TRISTIM_FIELDS_DEFINE(AbsoluteOptions, member<&AbsoluteOptions::transform>("transform"), member<&AbsoluteOptions::fusion>("fusion"),
               member<&AbsoluteOptions::w>("w"), member<&AbsoluteOptions::noise_floor>("noise_floor"),
               member<&AbsoluteOptions::saturation>("saturation"));

TRISTIM_FIELDS_DEFINE(AbsoluteRecipe, member<&AbsoluteRecipe::inputs>("inputs"), member<&AbsoluteRecipe::options>("options"));

}  // namespace fields

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
  auto number = [](const char* name, const char* label, double def, double lo, double hi, const char* what,
                   const char* unit = "") {
    OptionSpec o;
    o.name = name, o.type = "number", o.label = label, o.default_number = def, o.min = lo, o.max = hi, o.description = what;
    o.unit = unit;
    return o;
  };
  // Z_u, Z_c, Z_o are three disjoint intervals only for w > 2: the row says so (the page and --help).
  auto exclusive_min = [](OptionSpec o) {
    o.min_exclusive = true;
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
      exclusive_min(number("w", "Zone parameter w", 10, kZoneWidthMin, kZoneWidthMax,
                           "section 3.1: Z_c = [1/w, (w-1)/w] of the (S - n) interval is the reliable zone; more than 2")),
      number("noise_floor", "Noise floor n", 0, 0, 1e9, "eq (7), when no lens-cap frames are given", "DN"),
      number("saturation", "Saturation S", 0, 0, 1e9, "eq (7); 0: measured from the frames (where the body clips)", "DN"),
  };
}

std::vector<MethodInfo> absolute_sensitivity_table() {
  const std::string eq7 = std::string(citation::kGuarnera2018) + ", eq (7)";
  return {
      {"none", "none (A_R = A_G = A_B)", eq7 + " with the channel areas taken equal: no sensitivities known", {}},
      {"given", "Given curves (a CSV of R, G, B, or an estimate from a chart photo)",
       eq7 + ": the areas of curves given by the user, measured or estimated (Jiang, Liu, Gu & Süsstrunk 2013)", {}},
      {"camera", "A built-in camera's measured sensitivities", eq7 + ": the areas of one of the built-in cameras' curves",
       {}},
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
    throw Error(ErrorCode::InvalidArgument, "sensitivities: choice is one of " + ids_of(absolute_sensitivity_table()) + ", not '" + a.choice + "'");
  }
  return r;
}

// ---- JSON --------------------------------------------------------------------------------

json::Value absolute_recipe_json(const AbsoluteRecipe& in) {
  return fields::write_document(complete_absolute_recipe(in), kDocument);
}

std::string absolute_recipe_to_json(const AbsoluteRecipe& recipe) { return absolute_recipe_json(recipe).dump(2) + "\n"; }

AbsoluteRecipe absolute_recipe_from_json(const json::Value& o) {
  AbsoluteRecipe r;
  fields::read_document(o, r, kDocument, kAbsoluteRecipe);
  const SpectralData& ssf = r.inputs.sensitivities.ssf;
  if (r.inputs.sensitivities.choice == "given")
    for (size_t c = 0; c < 3; ++c)
      if (c >= ssf.size() || ssf.values[c].size() != ssf.wavelengths.size())
        throw Error(ErrorCode::RecipeInvalid, std::string("absolute recipe: inputs.sensitivities.") + "RGB"[c] +
                                                  " must have one value per wavelength");
  return complete_absolute_recipe(r);
}

AbsoluteRecipe absolute_recipe_from_json(const std::string& text) {
  return absolute_recipe_from_json(fields::parse_document(text, kDocument));
}

}  // namespace tristim

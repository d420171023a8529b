// CLI: `tristim absolute fit` — an absolute profile (Guarnera, Bianco & Schettini 2018) from an
// absolute recipe (made from the flags, or read with --recipe) and the frames it names, through
// characterise_absolute (tristim/absolute/characterise.hpp), the page's path too.
#include <iostream>
#include <optional>

#include "absolute_cli.hpp"
#include "patch_args.hpp"
#include "tristim/absolute/fields.hpp"
#include "tristim/error.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::cli {
namespace {

/// Frames a recipe names, decoded once each, and the AbsoluteFrames that point at them.
struct LoadedFrames {
  std::vector<RawImage> bracket, lens_cap, others;
  std::optional<RawImage> flat;
  AbsoluteFrames frames;
};

/// Decodes the frames of `r`: the bracket, lens cap and flat from `frame_base`, the frames region
/// rows name outside the bracket from `row_base` (locate_file: relative names from that folder).
void load_frames(const AbsoluteRecipe& r, const std::string& frame_base, const std::string& row_base, LoadedFrames& f) {
  for (const auto& n : r.inputs.bracket) f.bracket.push_back(load_raw_file(locate_file(n, frame_base)));
  for (const auto& n : r.inputs.lens_cap) f.lens_cap.push_back(load_raw_file(locate_file(n, frame_base)));
  if (!r.inputs.flat.empty()) f.flat = load_raw_file(locate_file(r.inputs.flat, frame_base));
  for (const auto& s : r.inputs.stimuli)
    if (s.region() && find_frame(r.inputs.bracket, s.file) < 0 && find_frame(f.frames.other_names, s.file) < 0) {
      f.others.push_back(load_raw_file(locate_file(s.file, row_base)));
      f.frames.other_names.push_back(s.file);
    }
  for (const auto& x : f.bracket) f.frames.bracket.push_back(&x);
  for (const auto& x : f.lens_cap) f.frames.lens_cap.push_back(&x);
  for (const auto& x : f.others) f.frames.others.push_back(&x);
  if (f.flat) f.frames.flat = &*f.flat;
}

/// An absolute recipe from the flags (stimuli rows from --stimuli, frames as named on the command line).
AbsoluteRecipe recipe_from_flags(const Args& args) {
  AbsoluteRecipe r;
  const std::string path = args.get("stimuli");
  r.inputs.stimuli = read_absolute_stimuli(read_file(path), path);
  r.inputs.lens_cap = args.all("dark");
  r.inputs.flat = args.get("flat", "");
  r.inputs.bracket = args.all("bracket");
  if (args.has("camera")) {
    r.inputs.sensitivities.choice = "camera";
    r.inputs.sensitivities.camera = args.get("camera");
  } else if (args.has("ssf")) {
    r.inputs.sensitivities.choice = "given";
    r.inputs.sensitivities.source = "file:" + args.get("ssf");
    r.inputs.sensitivities.ssf = read_ssf_csv(read_file(args.get("ssf")), args.get("ssf"));
  }
  bool frames = !r.inputs.bracket.empty();
  for (const auto& s : r.inputs.stimuli) frames = frames || s.region();
  if (args.has("saturation")) {
    r.options.saturation = args.get_double("saturation", 0);
    if (!(r.options.saturation > 0)) throw Error(ErrorCode::InvalidArgument, "--saturation must be a positive level in DN");
  } else if (!frames) {
    throw Error(ErrorCode::InvalidArgument, "per-patch stimuli need --saturation (the clip level in DN) or --bracket frames");
  }
  r.options.noise_floor = args.get_double("noise-floor", 0);
  r.options.w = args.get_double("w", 10);
  r.options.transform = args.get("transform", "T1");
  r.options.fusion = args.get("fusion", "weighted");
  return r;
}

/// The recipe of --recipe: a recipe file, or an absolute profile that embeds one.
AbsoluteRecipe recipe_file(const std::string& path) {
  const std::string text = read_file(path);
  json::Value v;
  try {
    v = json::parse(text);
  } catch (const Error&) {
    return absolute_recipe_from_json(text);  // says what is wrong with it as a recipe
  }
  const json::Value* format = v.is_object() ? v.find("format") : nullptr;
  if (format && format->is_string() && format->as_string() == "tristim-absolute-profile") {
    const AbsoluteProfile p = absolute_profile_from_json(text);
    if (!p.has_recipe) throw Error(ErrorCode::RecipeInvalid, "'" + path + "' is an absolute profile without a recipe");
    return p.recipe;
  }
  return absolute_recipe_from_json(v);
}

}  // namespace

int run_absolute_fit(const Args& args, std::ostream& out) {
  AbsoluteRecipe recipe;
  std::string frame_base, row_base;  // where relative names are read from ("": the working folder)
  if (args.has("recipe")) {
    // Every setting from the recipe; its files relative to the recipe's folder; inputs may be replaced.
    args.allow_only({"recipe", "stimuli", "dark", "flat", "bracket", "out", "recipe-out"});
    recipe = recipe_file(args.get("recipe"));
    frame_base = row_base = dirname_of(args.get("recipe"));
    if (args.has("stimuli")) {
      recipe.inputs.stimuli = read_absolute_stimuli(read_file(args.get("stimuli")), args.get("stimuli"));
      row_base = dirname_of(args.get("stimuli"));
    }
    if (args.has("dark") || args.has("flat") || args.has("bracket")) {
      if (args.has("dark")) recipe.inputs.lens_cap = args.all("dark");
      if (args.has("flat")) recipe.inputs.flat = args.get("flat");
      if (args.has("bracket")) recipe.inputs.bracket = args.all("bracket");
      frame_base.clear();
    }
  } else {
    args.allow_only({"stimuli", "dark", "flat", "bracket", "camera", "ssf", "noise-floor", "saturation", "w", "transform",
                     "fusion", "out", "recipe-out"});
    recipe = recipe_from_flags(args);
    row_base = dirname_of(args.get("stimuli"));  // region files are relative to the CSV
  }
  LoadedFrames loaded;  // lens-cap frames (n, eq 7), the flat (f(r)), the bracket, training frames: decoded once each
  load_frames(recipe, frame_base, row_base, loaded);
  const AbsoluteCharacterisation c = characterise_absolute(recipe, loaded.frames);
  const AbsoluteProfile& p = c.profile;
  const std::string profile = absolute_profile_to_json(p);
  // The summary: a picked part of the report the page gets (AbsoluteReport's lists, as `tristim
  // absolute evaluate --json` writes "training" and "fit").
  const json::Value s = fields::object(
      {{"training", fields::write_picked(c.report.training, {"luminance_stimuli", "colour_stimuli", "saturated_stimuli",
                                                             "figures"})},
       {"fit", fields::write_picked(c.report.fit, {"reciprocity_ok", "reciprocity_message", "exposures", "channels",
                                                   "saturation_fraction", "areas_source", "colour_status",
                                                   "colour_message"})}});
  if (p.areas_source == "none") std::cerr << "tristim absolute fit: no sensitivities given (--camera or --ssf): A_R = A_G = A_B\n";
  if (args.has("recipe-out")) {
    const std::string r = absolute_recipe_to_json(c.recipe);
    write_bytes(args.get("recipe-out"), r.data(), r.size());
  }
  if (args.has("out")) {
    write_bytes(args.get("out"), profile.data(), profile.size());
    out << s.dump() << "\n";
  } else {
    out << profile;
    std::cerr << s.dump() << "\n";
  }
  return 0;
}

}  // namespace tristim::cli

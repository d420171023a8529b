// CLI: `tristim fit` — a profile from a recipe (given, or made from the flags) and its inputs.
#include <algorithm>
#include <array>
#include <iostream>

#include "bootstrap_args.hpp"
#include "cli.hpp"
#include "patch_args.hpp"
#include "share_cli.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim::cli {
namespace {

const char* kFitUsage =
    "tristim fit --rgb patches.csv --xyz reference.csv --model <id> [--objective ls|psm|de2000]\n"
    "            [--white <patch id>] [--lab-white D50|D65|X,Y,Z] [--ref-white D50|D65|X,Y,Z]\n"
    "            [--out profile.json] [--csv patches_out.csv] [--no-loo] [--recipe-out recipe.json]\n"
    "            [--psm-max-iterations N] [--psm-threshold T] [--de-rms] [--de-algorithm auto|lm|irls|bobyqa|sbplx]\n"
    "            [--de-xtol X] [--de-ftol F] [--de-max-evaluations N] [--de-step S]\n"
    "            [--linearisation <id>[:name=value,...]]   (the recipe's linearisation stage: tristim linearise --list)\n"
    "            [--surface <method>:<name>=<value>,...]   (the recipe's surface stage: tristim surface methods)\n"
    "            [--bootstrap N [--seed 1] [--level 0.95]]\n"
    "tristim fit --recipe recipe.json (--rgb patches.csv | --raw chart.dng) [--xyz reference.csv]\n"
    "            [--out profile.json] [--csv patches_out.csv] [--recipe-out recipe.json]\n"
    "tristim fit --recipe recipe.json --raw a.dng [--dark d.dng ...] [--flat f.dng] --raw b.dng [...]\n"
    "            [--xyz ra.csv --xyz rb.csv] [--duplicates once|each]\n"
    "            [--out profile.json] [--csv patches_out.csv] [--recipe-out recipe.json]\n"
    "            (a recipe with an \"images\" list: one --raw per image, in its order; docs/multi-image.md)\n"
    "            --dark (repeatable, averaged) and --flat are the frames of the --raw before them (Abed 2013\n"
    "            App. C steps 1-2), applied in the image's capture.dark_mode and flat/fall-off choice\n"
    "            --xyz: none (built-in charts), one per --raw, or one per image whose reference is a file\n"
    "tristim fit --project p.tristim [--out profile.json]   (a project file: tristim share --project, the page's export)\n"
    "  Fits camera RGB -> XYZ and prints (or writes) the profile JSON with training and\n"
    "  leave-one-out metrics; the profile embeds the recipe it was made with.\n"
    "  --white preserves that patch exactly. Reference tables may be XYZ (Y = 100 for the perfect\n"
    "  diffuser) or L*a*b* (converted with --ref-white, default D50). --lab-white is the white of\n"
    "  the CIELAB errors and of the de2000 objective (default D50). --de-rms minimises the RMS\n"
    "  instead of the mean CIEDE2000. Models, objectives and linearisations: below (tristim models)\n"
    "  With --recipe every setting comes from the recipe (a profile's \"recipe\" or one the page\n"
    "  saved): --raw samples the chart with the recipe's layout and corners; without --xyz the\n"
    "  reference is the recipe's built-in chart under its illuminant and observer (after its surface\n"
    "  stage). The same recipe and inputs give the same coefficients as the page.\n"
    "  --surface corrects the reference reflectances for the capture geometry (Abed 2013 eqs 1-5): --xyz\n"
    "  is then a file with spectra (integrated under D50, 1931 observer) or a built-in chart id.\n"
    "  --model corrected-3x3 (Abed 2013 eqs 6-13, App. C eqs 26-28) needs --white <patch>, the white\n"
    "  reference: the 3x4 without its offset, scaled by mu from that white; mu is printed and written\n"
    "  to the profile as \"corrected_3x3\": {\"mu\": ...}.\n"
    "  --bootstrap N [--seed 1] [--level 0.95]: N resamples over the patches (and over each patch's pixels\n"
    "  when --rgb has sample's R_std,G_std,B_std,n columns, or a --raw is sampled here): \"ci\":\n"
    "  {\"level\",\"lo\",\"hi\"} next to the training and leave-one-out mean dE00, and \"bootstrap\": each\n"
    "  coefficient's interval, their covariance.";

/// A recipe from the flags of the classic form (every stage but characterisation and surface at its
/// default). `chart`: the built-in chart --xyz names ("" for a file).
Recipe recipe_from_flags(const Args& args, const PatchData& d, const std::string& chart) {
  int white_index = -1;
  const FitOptions o = fit_options(args, d, white_index);
  Recipe r;
  r.reference.chart = chart.empty() ? "file" : chart;
  if (chart.empty()) r.reference.data_digest = bytes_digest(read_files(args.all("xyz")));  // every --xyz
  if (args.has("surface")) r.surface = parse_choice(args.get("surface"));
  r.characterisation.model = args.get("model");
  r.characterisation.objective = objective_choice(o);
  r.characterisation.white_patch = white_index >= 0 ? d.ids[white_index] : "";
  r.characterisation.lab_white = o.white;
  r.evaluation.leave_one_out = !args.has("no-loo");
  if (args.has("linearisation")) r.linearisation = parse_choice(args.get("linearisation"));
  return complete_recipe(r);
}

/// Camera RGB paired with the recipe's built-in reference by id (every RGB patch must be in it).
PatchData pair_with_reference(const PatchTable& rgb, const ReferenceChart& ref, const std::string& rgb_path) {
  const PatchPairs pairs = pair_by_id(ref.ids, ref.XYZ, rgb.ids, rgb.RGB);
  if (!pairs.missing_in_reference.empty())
    throw Error(ErrorCode::PatchMismatch, "patch '" + patch_labels(rgb, {pairs.missing_in_reference.front()}).front() +
                                              "' of " + rgb_path +
                                              " is not in the recipe's chart '" + ref.chart_id + "'");
  PatchData d;
  d.ids = pairs.ids;
  d.labels = patch_labels(rgb, pairs.ids);
  d.rgb = to_matrix(pairs.measured);
  d.xyz = to_matrix(pairs.reference);
  return d;
}

/// The built-in chart id `value` names, or "" when it is not one (a file).
std::string builtin_chart(const std::string& value) {
  if (file_exists(value)) return "";
  for (const auto& c : list_charts())
    if (c.id == value) return c.id;
  return "";
}

/// The classic form's patches: --rgb paired with --xyz, a file (XYZ, Lab or spectra) or a built-in
/// chart id. A surface stage other than none corrects reflectances (Abed 2013 eqs 1-5), so it needs
/// spectra: a built-in chart (recipe_reference) or a file with spectra; both are integrated under
/// D50 and the 1931 observer (the recipe's reference defaults). `fit --recipe` with --rgb and an --xyz
/// file goes the same way, so its surface stage is applied again.
PatchData classic_pairs(const Args& args, const std::string& chart, const MethodChoice& surface) {
  const std::string rgb_path = args.get("rgb"), xyz_path = args.get("xyz");
  // Several --rgb: their union (patch_args.hpp). An RGB file may lack patches of its reference.
  if (args.all("rgb").size() > 1 || (chart.empty() && surface.method == "none")) {
    PatchData d = load_pairs(args, parse_white(args, "ref-white", whites::D50()), true);
    std::cerr << without_rgb_note("fit", "fitted", d);  // a chart cut by the frame: fitted on the patches it shows
    return d;
  }
  const PatchTable rgb = read_patch_file(read_file(rgb_path), rgb_path);
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": needs R, G, B columns");
  Recipe r;
  r.surface = surface;
  if (!chart.empty()) {
    r.reference.chart = chart;
    return pair_with_reference(rgb, recipe_reference(r), rgb_path);
  }
  PatchTable t = read_patch_file(read_file(xyz_path), xyz_path);
  if (!t.has_spectra)
    throw Error(ErrorCode::MissingColumn, "--surface " + surface.method + " corrects reflectances, but '" + xyz_path +
                                              "' has no spectra (give a spectral file or a built-in chart id as --xyz)");
  t.spectra = correct_surface(surface, t.spectra);
  t.has_XYZ = t.has_Lab = false;
  return pair_with_reference(rgb, reference_from_table(t, illuminant_spd(r.reference.illuminant),
                                                       parse_observer(r.reference.observer)), rgb_path);
}

/// The training set of a recipe; a TIFF/PNG/JPEG given with --raw also sets the recipe's capture
/// full scale (255 / 65535) when it has none, so its linearisation reads x = stored / full scale.
TrainingSet training_from_recipe(const Args& args, Recipe& recipe, PixelStats& pixels) {
  if (args.has("raw") == args.has("rgb"))
    throw Error(ErrorCode::InvalidArgument, "fit --recipe takes one of --rgb patches.csv or --raw chart image");
  const bool builtin = recipe.reference.chart != "file";
  if (!builtin && !args.has("xyz"))
    throw Error(ErrorCode::InvalidArgument, "the recipe's reference is a file: give it with --xyz");
  if (args.has("raw")) {
    const std::string path = args.get("raw"), bytes = read_file(path);
    RawImage image;
    try {
      image = decode_any(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const Error& e) {
      throw Error(e.code(), "'" + path + "': " + e.what());
    }
    // The page's sampling: a chart cut by the frame is sampled where it is inside (issue 48).
    LightTrap trap;
    const ChartSample sample = sample_recipe_chart(recipe, image, &trap);
    if (recipe.capture.has_light_trap())
      std::cerr << "light trap: flare R=" << trap.mean[0] << " G=" << trap.mean[1] << " B=" << trap.mean[2]
                << " DN (recipe: " << recipe.capture.flare[0] << " " << recipe.capture.flare[1] << " "
                << recipe.capture.flare[2] << ")\n";
    for (const PatchSample& q : sample.patches)
      pixels[normalise_patch_id(q.id)] = {Vec3(q.std[0], q.std[1], q.std[2]), static_cast<double>(q.n)};
    if (builtin && !args.has("xyz")) return training_set(recipe, sample, recipe_reference(recipe));
    const std::string xyz_path = args.get("xyz");
    const PatchTable t = read_patch_file(read_file(xyz_path), xyz_path);
    const ReferenceChart ref = reference_from_table(t, illuminant_spd(recipe.reference.illuminant),
                                                    parse_observer(recipe.reference.observer));
    return training_set(recipe, sample, ref);
  }
  const std::string rgb_path = args.get("rgb");
  if (args.has("xyz")) {
    const PatchData d = classic_pairs(args, "", recipe.surface);
    return training_set(recipe, d.labels, d.rgb, d.xyz);  // the labels: the keys are their normalised forms
  }
  const PatchTable rgb = read_patch_file(read_file(rgb_path), rgb_path);
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": needs R, G, B columns");
  const PatchData d = pair_with_reference(rgb, recipe_reference(recipe), rgb_path);
  return training_set(recipe, d.labels, d.rgb, d.xyz);
}

/// The frame files of each --raw: every --dark (repeatable) and --flat belongs to the --raw before it
/// (`--raw a.dng --dark a_d1.dng --dark a_d2.dng --raw b.dng --flat b_flat.dng`).
struct FramePaths {
  std::vector<std::string> darks, flats;
};
std::vector<FramePaths> frames_of_raws(const Args& args, size_t raws) {
  std::vector<FramePaths> paths(raws);
  size_t seen = 0;
  for (const auto& [key, value] : args.in_order) {
    if (key == "raw") ++seen;
    if (key != "dark" && key != "flat") continue;
    if (seen == 0)
      throw Error(ErrorCode::InvalidArgument, "--" + key + " '" + value +
                                                  "' comes before any --raw: give each image's frames after its --raw");
    (key == "dark" ? paths[seen - 1].darks : paths[seen - 1].flats).push_back(value);
  }
  return paths;
}

/// The decoded frames of one image; a file that does not read or decode is named with its option.
RecipeImageFrames load_frames(const FramePaths& paths) {
  RecipeImageFrames frames;
  const auto load = [](const std::string& option, const std::string& path) {
    try {
      return load_raw(path);
    } catch (const Error& e) {
      throw Error(e.code(), "--" + option + " '" + path + "': " + e.what());
    }
  };
  for (const auto& d : paths.darks) frames.darks.push_back(load("dark", d));
  for (const auto& f : paths.flats) frames.flat.push_back(load("flat", f));
  return frames;
}

/// The training set of a recipe with an "images" list (issue 48): each --raw sampled with its image
/// entry (recipe.images[k], which records the file's SHA-256 and the flare measured) and the frames
/// given after it, paired with that entry's reference (its built-in chart, or the --xyz at the same
/// position; or, with one --xyz per image whose reference is a file, that image's in order, the
/// others their built-in chart), and the union.
TrainingSet training_from_images(const Args& args, Recipe& recipe) {
  const std::vector<std::string> raws = args.all("raw"), xyzs = args.all("xyz");
  if (args.has("rgb")) throw Error(ErrorCode::InvalidArgument, "a recipe with images takes --raw (one per image), not --rgb");
  if (raws.size() != recipe.images.size())
    throw Error(ErrorCode::InvalidArgument, "the recipe lists " + std::to_string(recipe.images.size()) + " images but " +
                                                std::to_string(raws.size()) + " --raw were given (one per image, in order)");
  const size_t files = static_cast<size_t>(std::count_if(recipe.images.begin(), recipe.images.end(),
                                                         [](const RecipeImage& e) { return e.reference.chart == "file"; }));
  if (!xyzs.empty() && xyzs.size() != raws.size() && xyzs.size() != files)
    throw Error(ErrorCode::InvalidArgument, "--xyz: give none (built-in references), one per --raw, or one per image whose "
                                            "reference is a file (" + std::to_string(files) + "), not " +
                                                std::to_string(xyzs.size()));
  const bool per_file = !xyzs.empty() && xyzs.size() != raws.size();  // --xyz only for the file references
  size_t next_xyz = 0;
  if (args.has("duplicates")) recipe.duplicates = args.get("duplicates");
  const std::vector<FramePaths> frame_paths = frames_of_raws(args, raws.size());
  std::vector<ChartPart> parts;
  for (size_t k = 0; k < raws.size(); ++k) {
    RecipeImage& entry = recipe.images[k];
    const std::string named = "images[" + std::to_string(k) + "] ('" + entry.name + "'): ";
    std::string bytes;
    try {
      bytes = read_file(raws[k]);
    } catch (const Error& e) {
      throw Error(e.code(), named + e.what());
    }
    RecipeImageFrames frames;
    try {
      frames = load_frames(frame_paths[k]);
    } catch (const Error& e) {
      throw Error(e.code(), named + e.what());
    }
    const std::vector<ChartSample> samples =
        sample_recipe_image(entry, k, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), frames);
    const Recipe own = image_recipe(recipe, entry);
    try {
      if (entry.reference.chart == "file" && xyzs.empty())
        throw Error(ErrorCode::InvalidArgument, "its reference is a file: give one --xyz per --raw");
      ReferenceChart ref;
      if (xyzs.empty() || (per_file && entry.reference.chart != "file")) {
        ref = recipe_reference(own);
      } else {
        const std::string& path = per_file ? xyzs[next_xyz++] : xyzs[k];
        const PatchTable t = read_patch_file(read_file(path), path);
        ref = reference_from_table(t, illuminant_spd(own.reference.illuminant), parse_observer(own.reference.observer));
      }
      for (size_t j = 0; j < samples.size(); ++j)
        parts.push_back({entry.name + (samples.size() > 1 ? " #" + std::to_string(j + 1) : ""),
                         training_set(own, samples[j], ref)});
    } catch (const Error& e) {
      throw Error(e.code(), named + e.what());
    }
  }
  return training_union(recipe, parts);
}

/// --bootstrap: the intervals (evaluation/bootstrap.hpp) of the characterisation `c` written into
/// its profile JSON `p`: "ci" next to the training and leave-one-out mean CIEDE2000 in "metrics",
/// and a "bootstrap" object with each coefficient's interval, their covariance and each patch's
/// predicted-XYZ covariance.
void add_bootstrap(const Args& args, const Characterisation& c, const TrainingSet& training, const PixelStats& pixels,
                   json::Value& p) {
  int white_index = -1;
  const FitOptions options = recipe_fit_options(c.recipe, training.ids, c.linear_RGB, c.reference_XYZ, white_index);
  const bool linear = c.linearisation.choice.method == "identity";
  BootstrapOptions b = bootstrap_options(args, "fit", args.has("rgb") ? args.get("rgb") : "", training.ids, linear);
  if (linear && !pixels.empty()) set_pixel_stats(b, training.ids, pixels);  // --raw: the pixels this run sampled
  if (c.evaluation.has_loo) b.loo_dE00 = c.evaluation.loo.patches.dE00;
  const BootstrapResult r = bootstrap_fit(c.recipe.characterisation.model, c.linear_RGB, c.reference_XYZ, options, b);
  add_bootstrap_to_profile(p, r, c.profile.model);
  std::cerr << "tristim fit: bootstrap (" << r.resamples << " resamples, " << (r.pixels ? "patches and pixels" : "patches")
            << "): training mean dE00 " << fmt(r.level * 100, 0) << " % interval [" << fmt(r.train_dE00_mean.lo) << ", "
            << fmt(r.train_dE00_mean.hi) << "]";
  if (r.has_loo) std::cerr << ", leave-one-out [" << fmt(r.loo_dE00_mean.lo) << ", " << fmt(r.loo_dE00_mean.hi) << "]";
  std::cerr << "\n";
}

int run_fit(const Args& args, std::ostream& out) {
  if (args.has("project")) return run_fit_project(args, out);  // a .tristim project (cmd_share.cpp)
  TrainingSet training;
  Recipe recipe;
  PixelStats pixels;  // filled when a single --raw is sampled here
  if (args.has("recipe")) {
    std::vector<std::string> known{"recipe", "rgb", "raw", "xyz", "ref-white", "out", "csv", "recipe-out", "duplicates"};
    for (const auto& b : bootstrap_option_names()) known.push_back(b);
    recipe = recipe_from_json(read_file(args.get("recipe")));
    if (!recipe.images.empty()) known.insert(known.end(), {"dark", "flat"});  // per image: after its --raw
    args.allow_only(known);
    if (args.has("duplicates") && recipe.images.empty())
      throw Error(ErrorCode::InvalidArgument, "--duplicates applies to a recipe with an \"images\" list");
    training = recipe.images.empty() ? training_from_recipe(args, recipe, pixels) : training_from_images(args, recipe);
  } else {
    std::vector<std::string> known{"rgb", "xyz", "model", "objective", "white", "lab-white", "ref-white", "out", "csv",
                                   "psm-max-iterations", "psm-threshold", "de-algorithm", "de-xtol", "de-ftol",
                                   "de-max-evaluations", "de-rms", "de-step", "no-loo", "recipe-out", "linearisation",
                                   "surface"};
    for (const auto& b : bootstrap_option_names()) known.push_back(b);
    args.allow_only(known);
    const std::string chart = builtin_chart(args.get("xyz"));
    const PatchData d = classic_pairs(args, chart, parse_choice(args.get("surface", "none")));
    recipe = recipe_from_flags(args, d, chart);
    training = training_set(recipe, d.labels, d.rgb, d.xyz);
  }
  for (const auto& e : training.excluded) std::cerr << "tristim fit: left out " << e << "\n";
  const Characterisation c = characterise(recipe, training);
  if (!c.linearisation.message.empty())  // e.g. Shen2008 extrapolated: the profile's "extrapolated"
    std::cerr << "tristim fit: warning: " << c.linearisation.message << "\n";
  const ModelEvaluation& ev = c.evaluation;
  std::string text = profile_to_json(c.profile);
  const std::vector<ChartFigures> charts = chart_figures(c, training);  // several charts: each one's figures
  if (c.recipe.characterisation.model == kCorrected3x3 || args.has("bootstrap") || !charts.empty()) {
    json::Value p = json::parse(text);
    if (!charts.empty()) p.set("charts", fields::write(charts));  // ChartFigures' field list
    if (c.recipe.characterisation.model == kCorrected3x3) {  // μ of Abed 2013 eq (27), beside the profile
      p.set("corrected_3x3", fields::object({{"mu", ev.fit.mu}, {"white_patch", c.recipe.characterisation.white_patch}}));
      std::cerr << "tristim fit: corrected 3x3, white scaling mu = " << fmt(ev.fit.mu, 6) << " (Abed 2013 eq 27)\n";
    }
    if (args.has("bootstrap")) add_bootstrap(args, c, training, pixels, p);
    text = p.dump(2) + "\n";
  }
  if (args.has("recipe-out")) {
    const std::string r = recipe_to_json(c.recipe);
    write_bytes(args.get("recipe-out"), r.data(), r.size());
  }
  if (args.has("csv")) {
    const std::string csv = patch_csv(training.labels, c.linear_RGB, training.reference_XYZ, ev.fit.fitted,
                                      c.recipe.characterisation.lab_white, ev.has_loo ? ev.loo_XYZ : PatchMatrix());
    write_bytes(args.get("csv"), csv.data(), csv.size());
  }
  if (args.has("out")) {
    write_bytes(args.get("out"), text.data(), text.size());
    std::cerr << "tristim fit: " << c.recipe.characterisation.model << " (" << objective_id(ev.fit.objective)
              << ") training mean dE00 " << fmt(ev.training.dE00.mean) << ", leave-one-out mean dE00 "
              << (ev.has_loo ? fmt(ev.loo.dE00.mean) : std::string("-")) << ", status "
              << fit_status_name(ev.fit.status) << (ev.fit.message.empty() ? "" : " (" + ev.fit.message + ")") << "\n";
    std::cerr << per_chart_figures(args, training.labels, ev);  // several --rgb: each chart's figures
  } else {
    out << text;
  }
  std::cerr << chart_figures_text(charts);
  return 0;
}

const CommandRegistration reg_fit({"fit", "fit a camera characterisation model -> profile JSON", kFitUsage, run_fit,
                                   fit_methods_help});

}  // namespace
}  // namespace tristim::cli

// CLI: `tristim share` (a reproducible link from a profile and the data it was fitted on) and
// `tristim reproduce` (recompute a link, payload or .tristim project and compare the digest).
#include <iostream>

#include "cli.hpp"
#include "patch_args.hpp"
#include "share_cli.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/absolute/characterise.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/share/link.hpp"
#include "tristim/share/sha256.hpp"

namespace tristim::cli {

namespace {

const char* kShareUsage =
    "tristim share --profile p.json [--raw chart.dng | --rgb patches.csv] [--xyz reference.csv]\n"
    "              [--base URL] [--payload] [--project out.tristim]\n"
    "tristim share --profile absolute-profile.json [--base URL] [--payload]\n"
    "  Prints a link that recomputes the profile: its recipe, the per-patch camera RGB, the reference\n"
    "  (a built-in chart by id, or --xyz inline), the SHA-256 of the RAW and a digest of the expected\n"
    "  results, compressed into the URL fragment (nothing is uploaded). A profile holds its training\n"
    "  patches, so it needs nothing else; --raw / --rgb / --xyz give the inputs it was fitted on\n"
    "  instead (a profile of an older tristim, or to record the RAW's SHA-256); either way they are\n"
    "  fitted again and must give the profile's results. --base: the page's address (default\n"
    "  http://127.0.0.1:8080/); --payload: the payload alone. --project also writes a project file holding the payload and the RAW.\n"
    "  An absolute profile (tristim absolute fit) whose stimuli are per-patch rows needs no inputs.\n"
    "  Format: docs/link-format.md.";

const char* kReproduceUsage =
    "tristim reproduce '<link, payload or .tristim file>' [--json] [--out profile.json]\n"
    "  Recomputes the profile from the data in the link and compares it with the link's digest of\n"
    "  the expected results. Exit 0: \"reproduced\"; exit 1: \"differs\" (both results, line by line);\n"
    "  exit 2: the link is damaged, truncated, too large or of another format version (a coded error).\n"
    "  --json prints {\"verdict\", \"expected\", \"actual\", \"differences\", …}; --out writes the recomputed profile.";

constexpr const char* kDefaultBase = "http://127.0.0.1:8080/";

std::string base_name(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// The training set of `recipe` from --raw or --rgb (and --xyz), as `tristim fit --recipe` reads them.
TrainingSet share_inputs(const Args& args, const Profile& profile, Recipe& recipe, std::vector<ShareSource>& sources,
                         std::string& raw_bytes) {
  const bool builtin = !share_inline_reference(recipe);
  if (!args.has("raw") && !args.has("rgb") && !args.has("xyz") && profile.has_training_data) {
    // The profile's own training patches (characterise() keeps them): camera RGB as sampled,
    // the reference by chart id, or inline when it was a file.
    if (!builtin) return training_set(recipe, profile.training_labels, profile.training_camera_RGB, profile.training_reference_XYZ);
    SharePayload tables;
    tables.recipe = recipe;
    tables.labels = profile.training_labels;
    tables.camera_RGB = profile.training_camera_RGB;
    return share_training(tables);
  }
  if (args.has("raw") == args.has("rgb"))
    throw Error(ErrorCode::InvalidArgument, "share needs the profile's inputs: one of --raw chart image or --rgb patches.csv "
                                            "(this profile does not hold its training patches: made by an older tristim?)");
  if (!builtin && !args.has("xyz"))
    throw Error(ErrorCode::InvalidArgument, "the profile's reference is a file: give it with --xyz");
  SharePayload tables;  // the patch tables as a link would carry them (share_training pairs them)
  tables.recipe = recipe;
  if (args.has("raw")) {
    const std::string path = args.get("raw");
    raw_bytes = read_file(path);
    sources.push_back({base_name(path), sha256_hex(raw_bytes)});
    RawImage image;
    try {
      image = decode_any(reinterpret_cast<const std::uint8_t*>(raw_bytes.data()), raw_bytes.size());
    } catch (const Error& e) {
      throw Error(e.code(), "'" + path + "': " + e.what());
    }
    if (builtin && !args.has("xyz")) return sample_training(recipe, image);
    const PatchTable t = read_patch_file(read_file(args.get("xyz")), args.get("xyz"));
    const ReferenceChart ref =
        reference_from_table(t, illuminant_spd(recipe.reference.illuminant), parse_observer(recipe.reference.observer));
    return sample_training(recipe, image, &ref);
  }
  if (args.has("xyz")) {
    const PatchData d = load_pairs(args.get("rgb"), args.get("xyz"), parse_white(args, "ref-white", whites::D50()));
    return training_set(recipe, d.labels, d.rgb, d.xyz);
  }
  const PatchTable rgb = read_patch_file(read_file(args.get("rgb")), args.get("rgb"));
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, args.get("rgb") + ": needs R, G, B columns");
  tables.labels = rgb.labels;
  tables.camera_RGB = to_matrix(rgb.RGB);
  return share_training(tables);
}

/// The link of an absolute profile: its recipe's per-patch stimuli fitted again, the results checked.
std::string share_absolute(const std::string& profile_path, const std::string& text) {
  const AbsoluteProfile profile = absolute_profile_from_json(text);
  if (!profile.has_recipe) throw Error(ErrorCode::ProfileInvalid, profile_path + " has no recipe (made before recipes existed): fit it again");
  const SharePayload payload = share_payload(characterise_absolute(profile.recipe, AbsoluteFrames{}));
  const ShareResults given = share_results(profile);
  if (payload.expected.digest != given.digest)
    throw Error(ErrorCode::PatchMismatch, "the recipe of " + profile_path + " does not give its results again (another tristim "
                                          "version?): expected\n" + given.text + "got\n" + payload.expected.text);
  return encode_share_payload(payload);
}

void print_link(const Args& args, const std::string& payload, std::ostream& out) {
  const std::string link = share_link(args.get("base", kDefaultBase), payload);
  if (link.size() > kLinkLengthLimit)
    std::cerr << "tristim share: the link has " << link.size() << " characters (more than " << kLinkLengthLimit
              << "): some programs cut such links; --project writes a project file instead\n";
  out << (args.has("payload") ? payload : link) << "\n";
}

int run_share(const Args& args, std::ostream& out) {
  args.allow_only({"profile", "raw", "rgb", "xyz", "ref-white", "base", "payload", "project"});
  const std::string profile_path = args.get("profile");
  const std::string profile_text = read_file(profile_path);
  if (profile_text.find("\"tristim-absolute-profile\"") != std::string::npos) {  // per-patch stimuli: no inputs
    for (const char* k : {"raw", "rgb", "xyz", "project"})
      if (args.has(k)) throw Error(ErrorCode::InvalidArgument, std::string("--") + k + " is for a relative profile: an absolute profile's recipe holds its stimuli");
    print_link(args, share_absolute(profile_path, profile_text), out);
    return 0;
  }
  const Profile profile = profile_from_json(profile_text);
  if (!profile.has_recipe)
    throw Error(ErrorCode::ProfileInvalid, profile_path + " has no recipe (made before recipes existed): fit it again");
  Recipe recipe = profile.recipe;
  std::vector<ShareSource> sources;
  std::string raw_bytes;
  const TrainingSet training = share_inputs(args, profile, recipe, sources, raw_bytes);
  const Characterisation c = characterise(recipe, training);
  const SharePayload payload = share_payload(c, training, sources);
  const ShareResults given = share_results(profile);
  if (payload.expected.digest != given.digest)
    throw Error(ErrorCode::PatchMismatch, "these inputs do not give " + profile_path + "'s results (is it the data it was fitted on, "
                                          "with this tristim version?): expected\n" + given.text + "got\n" + payload.expected.text);
  const std::string text = encode_share_payload(payload);
  if (args.has("project")) {
    Project project;
    project.payload = payload;
    if (!raw_bytes.empty()) project.images.push_back({sources.front().name, {raw_bytes.begin(), raw_bytes.end()}});
    const std::string bytes = project_to_bytes(project);
    write_bytes(args.get("project"), bytes.data(), bytes.size());
  }
  print_link(args, text, out);
  return 0;
}

/// A link, a payload, a file holding one, or a .tristim project (sampled again from its image when
/// it holds the source), recomputed.
Reproduction reproduce_input(const std::string& arg) {
  if (arg.find('#') == std::string::npos && arg.size() < 4096 && file_exists(arg)) {
    const std::string bytes = read_file(arg);
    if (is_project_file(bytes)) return reproduce_project(project_from_bytes(bytes));
    return reproduce_link(bytes);
  }
  return reproduce_link(arg);
}

void print_reproduction(const Reproduction& r, std::ostream& out) {
  const std::string versions = "link made with tristim " + r.expected_version + ", this is " + r.actual_version;
  if (r.verdict == "reproduced") {
    out << "reproduced (" << versions << (r.resampled ? "; patches sampled again from the image" : "") << "), "
        << r.actual.digest << "\n";
    std::string line;
    for (std::size_t i = 0; i < r.actual.text.size(); ++i) {
      if (r.actual.text[i] != '\n') { line += r.actual.text[i]; continue; }
      out << "  " << line << "\n";
      line.clear();
    }
    return;
  }
  out << "differs (" << versions << "): " << r.differences.size() << " result(s)\n";
  for (const auto& d : r.differences)
    out << "  " << d.name << "\n    link: " << (d.expected.empty() ? "(absent)" : d.expected)
        << "\n    now:  " << (d.actual.empty() ? "(absent)" : d.actual) << "\n";
}

int run_reproduce(const Args& args, std::ostream& out) {
  try {
    args.allow_only({"json", "out"});
    if (args.positional.size() != 1)
      throw Error(ErrorCode::InvalidArgument, "reproduce takes one link, payload or .tristim file");
    const Reproduction r = reproduce_input(args.positional[0]);
    if (args.has("out")) write_bytes(args.get("out"), r.profile.data(), r.profile.size());
    if (args.has("json")) out << reproduction_json(r).dump(2) << "\n";
    else print_reproduction(r, out);
    return r.verdict == "reproduced" ? 0 : 1;
  } catch (const Error& e) {  // exit 2: a bad link is not a "differs"
    std::cerr << "tristim reproduce: error " << e.code_name() << ": " << e.what() << "\n";
    return 2;
  }
}

const CommandRegistration reg_share({"share", "a reproducible link to a profile (recipe + patch data in the URL)", kShareUsage,
                                     run_share});
const CommandRegistration reg_reproduce({"reproduce", "recompute a shared link or .tristim project and check its digest",
                                         kReproduceUsage, run_reproduce});

}  // namespace

int run_fit_project(const Args& args, std::ostream& out) {
  args.allow_only({"project", "out"});
  const std::string path = args.get("project");
  const std::string bytes = read_file(path);
  const Reproduction r = reproduce_project(project_from_bytes(bytes));
  if (args.has("out")) write_bytes(args.get("out"), r.profile.data(), r.profile.size());
  else out << r.profile;
  std::cerr << "tristim fit: " << path << ": " << r.verdict << " against the project's expected results"
            << (r.resampled ? " (patches sampled again from its image)" : "") << "\n";
  return 0;
}

}  // namespace tristim::cli

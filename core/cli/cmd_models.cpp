// CLI: evaluate, compare, apply, export, models (characterisation models and profiles; fit: cmd_fit.cpp).
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "linearise_option.hpp"
#include "patch_args.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/io/json.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/capture/raw.hpp"

namespace tristim::cli {
namespace {
const char* kEvaluateUsage =
    "tristim evaluate --profile p.json --rgb test.csv --xyz ref.csv [--ref-white ...] [--csv out.csv]\n"
    "  Applies the profile to the test patches and prints JSON metrics (per patch and summaries).";

int run_evaluate(const Args& args, std::ostream& out) {
  args.allow_only({"profile", "rgb", "xyz", "ref-white", "csv"});
  const Profile p = profile_from_json(read_file(args.get("profile")));
  const PatchData d = load_pairs(args.get("rgb"), args.get("xyz"), parse_white(args, "ref-white", whites::D50()));
  validate_patches(d.rgb, d.xyz);
  const PatchMatrix est = profile_predict(p, d.rgb);  // (a profile with a linearisation takes stored values)
  const Metrics m = evaluate(est, d.xyz, p.white);
  json::Value o = json::Value::object();
  o.set("model", p.model.id);
  o.set("objective", objective_id(p.objective));
  o.set("white", json::Value(std::vector<double>{p.white[0], p.white[1], p.white[2]}));
  o.set("patches", static_cast<int>(d.rgb.rows()));
  o.set("same_data_as_training", training_digest(d.ids, d.rgb, d.xyz) == p.training_digest);
  o.set("metrics", metrics_json(m, d.labels, true));
  out << o.dump(2) << "\n";
  if (args.has("csv")) {
    const std::string csv = patch_csv(d.labels, d.rgb, d.xyz, est, p.white);
    write_bytes(args.get("csv"), csv.data(), csv.size());
  }
  return 0;
}

const char* kCompareUsage =
    "tristim compare --rgb patches.csv --xyz reference.csv [--objectives ls,psm,de2000]\n"
    "                [--models id,id,...] [--white <patch>] [--lab-white ...] [--ref-white ...]\n"
    "                [--test-rgb other.csv --test-xyz other_ref.csv] [--json] [--threads N]\n"
    "                [--linearisation <id>[:options]|fitted.json [--reflectances spectra.csv|<chart>] [--full-scale 255]]\n"
    "  Every model × objective on the same patches: training and leave-one-out CIEDE2000,\n"
    "  sorted by the held-out mean. With --test-rgb/--test-xyz also the train-on-one /\n"
    "  test-on-another table (Abed 2013 Table IV layout). The rows run on --threads threads\n"
    "  (default 0: one per hardware thread, at most 16); the numbers do not depend on it.";

json::Value compare_row_json(const CompareRow& r) {
  json::Value o = json::Value::object();
  o.set("model", r.model_id);
  o.set("objective", objective_id(r.objective));
  o.set("n_terms", r.n_terms);
  o.set("ok", r.ok);
  o.set("error_code", r.error_code);
  o.set("status", r.ok ? fit_status_name(r.status) : "error");
  o.set("message", r.message);
  o.set("condition_number", r.condition_number);
  o.set("seconds", r.seconds);
  o.set("cpu_seconds", r.cpu_seconds);
  o.set("train_dE00", summary_json(r.train_dE00));
  o.set("train_dE_xyz", summary_json(r.train_dE_xyz));
  o.set("has_loo", r.has_loo);
  if (r.has_loo) {
    o.set("loo_dE00", summary_json(r.loo_dE00));
    o.set("loo_dE_xyz", summary_json(r.loo_dE_xyz));
  }
  return o;
}

int run_compare(const Args& args, std::ostream& out) {
  args.allow_only({"rgb", "xyz", "objectives", "models", "white", "lab-white", "ref-white", "test-rgb",
                   "test-xyz", "json", "objective", "psm-max-iterations", "psm-threshold", "de-algorithm", "de-xtol",
                   "de-ftol", "de-max-evaluations", "de-rms", "de-step", "linearisation", "reflectances", "full-scale",
                   "threads"});
  if (args.has("threads")) {
    const double n = args.get_double("threads", 0);
    if (!(n >= 0 && n <= 256 && n == static_cast<int>(n)))
      throw Error(ErrorCode::InvalidArgument, "--threads must be a whole number from 0 (one per hardware thread) to 256, got '" +
                                                  args.get("threads") + "'");
    set_compare_threads(static_cast<int>(n));
  }
  const Vec3 ref_white = parse_white(args, "ref-white", whites::D50());
  PatchData d = load_pairs(args.get("rgb"), args.get("xyz"), ref_white);
  const Linearisation lin = linearisation_option(args, "compare", d.ids, d.rgb, d.xyz, ref_white);  // linearise_option.hpp
  int white_index = -1;
  const FitOptions o = fit_options(args, d, white_index);
  std::vector<Objective> objectives;
  for (const auto& s : split_list(args.get("objectives", "ls,psm,de2000"))) objectives.push_back(objective_from_id(s));
  std::vector<std::string> models;
  if (args.has("models"))
    for (const auto& s : split_list(args.get("models"))) models.push_back(model_info(s).id);
  const auto rows = compare_models(d.rgb, d.xyz, o, models, objectives, white_index);
  std::vector<TransferCell> transfer;
  if (args.has("test-rgb") || args.has("test-xyz")) {
    PatchData t = load_pairs(args.get("test-rgb"), args.get("test-xyz"), ref_white);
    t.rgb = linearise(lin, t.rgb);
    std::vector<std::string> ids = models;
    if (ids.empty())
      for (const auto& m : model_table())
        if (m.duplicate_of.empty()) ids.push_back(m.id);
    transfer = transfer_table({{args.get("rgb"), d.rgb, d.xyz}}, t.rgb, t.xyz, ids, objectives, o);
  }
  if (args.has("json")) {
    json::Value j = json::Value::object();
    j.set("patches", static_cast<int>(d.rgb.rows()));
    json::Value a = json::Value::array();
    for (const auto& r : rows) a.push(compare_row_json(r));
    j.set("rows", a);
    if (!transfer.empty()) {
      json::Value tj = json::Value::array();
      for (const auto& c : transfer) {
        json::Value cj = json::Value::object();
        cj.set("training_set", c.training_set);
        cj.set("model", c.model_id);
        cj.set("objective", objective_id(c.objective));
        cj.set("ok", c.ok);
        cj.set("error_code", c.error_code);
        cj.set("dE_xyz", summary_json(c.dE_xyz));
        cj.set("dE00", summary_json(c.dE00));
        tj.push(cj);
      }
      j.set("transfer", tj);
    }
    out << j.dump(2) << "\n";
    return 0;
  }
  out << "# " << d.rgb.rows() << " patches; CIEDE2000 relative to white " << fmt(o.white[0], 4) << ","
      << fmt(o.white[1], 4) << "," << fmt(o.white[2], 4) << "; sorted by leave-one-out mean\n";
  out << std::left << std::setw(18) << "model" << std::setw(8) << "obj" << std::right << std::setw(6) << "terms"
      << std::setw(10) << "train" << std::setw(10) << "train" << std::setw(10) << "LOO" << std::setw(10) << "LOO"
      << std::setw(10) << "LOO" << std::setw(11) << "cond" << "  status\n";
  out << std::left << std::setw(18) << "" << std::setw(8) << "" << std::right << std::setw(6) << "" << std::setw(10)
      << "mean" << std::setw(10) << "max" << std::setw(10) << "mean" << std::setw(10) << "p95" << std::setw(10) << "max"
      << std::setw(11) << "" << "\n";
  for (const auto& r : rows) {
    out << std::left << std::setw(18) << r.model_id << std::setw(8) << objective_id(r.objective) << std::right
        << std::setw(6) << r.n_terms;
    if (!r.ok) {
      out << "  refused: " << r.error_code << " (" << r.message << ")\n";
      continue;
    }
    std::ostringstream cond;
    cond << std::setprecision(2) << std::scientific << r.condition_number;
    out << std::setw(10) << fmt(r.train_dE00.mean) << std::setw(10) << fmt(r.train_dE00.max) << std::setw(10)
        << (r.has_loo ? fmt(r.loo_dE00.mean) : "-") << std::setw(10) << (r.has_loo ? fmt(r.loo_dE00.p95) : "-")
        << std::setw(10) << (r.has_loo ? fmt(r.loo_dE00.max) : "-") << std::setw(11) << cond.str() << "  "
        << fit_status_name(r.status) << "\n";
  }
  if (!transfer.empty()) {
    out << "\n# train on " << args.get("rgb") << ", test on " << args.get("test-rgb")
        << " (Abed 2013 Table IV layout): mean / max\n";
    out << std::left << std::setw(18) << "model" << std::setw(8) << "obj" << std::right << std::setw(12) << "dE_xyz mean"
        << std::setw(12) << "dE_xyz max" << std::setw(10) << "dE00 mean" << std::setw(10) << "dE00 max" << "\n";
    for (const auto& c : transfer) {
      out << std::left << std::setw(18) << c.model_id << std::setw(8) << objective_id(c.objective) << std::right;
      if (!c.ok) {
        out << "  refused: " << c.error_code << "\n";
        continue;
      }
      out << std::setw(12) << fmt(c.dE_xyz.mean, 4) << std::setw(12) << fmt(c.dE_xyz.max, 4) << std::setw(10)
          << fmt(c.dE00.mean) << std::setw(10) << fmt(c.dE00.max) << "\n";
    }
  }
  return 0;
}

const char* kApplyUsage =
    "tristim apply <profile.json> <image> --out xyz.tiff|xyz.pfm [--linearisation gamma|sRGB|fitted.json [--full-scale 255]]\n"
    "  Applies the profile to a camera-RGB image and writes 32-bit float XYZ (TIFF,\n"
    "  uncompressed, or PFM). Input: a RAW file (decoded like the chart: linear, black subtracted,\n"
    "  no white balance), a TIFF/PNG/JPEG (values as stored) or a colour PFM of camera RGB. A\n"
    "  profile fitted with a linearisation stage (fit --linearisation) linearises the stored values\n"
    "  itself; --linearisation is for profiles without one (e.g. a RAW profile on a gamma image).";

int run_apply(const Args& args, std::ostream&) {
  args.allow_only({"out", "linearisation", "full-scale"});
  if (args.positional.size() != 2)
    throw Error(ErrorCode::InvalidArgument, "usage: tristim apply <profile.json> <image> --out xyz.tiff|pfm");
  const Profile p = profile_from_json(read_file(args.positional[0]));
  const std::string in_path = args.positional[1];
  Image3f rgb;
  if (ext_of(in_path) == "pfm") {
    rgb = read_pfm(read_file(in_path));
  } else {
    // A RAW file: LibRaw's linear camera RGB (black subtracted, no white balance, half size for
    // Bayer sensors), the same data the chart patches are sampled from; a TIFF/PNG/JPEG: its
    // values as stored (recognised by its bytes, like `sample`).
    const std::string bytes = read_file(in_path);
    RawImage raw;
    try {
      raw = decode_any(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const Error& e) {
      throw Error(e.code(), "'" + in_path + "': " + e.what());
    }
    rgb.width = raw.width;
    rgb.height = raw.height;
    rgb.pixels = std::move(raw.rgb);
  }
  if (p.has_linearisation && args.has("linearisation"))
    throw Error(ErrorCode::InvalidArgument, "the profile has its own linearisation stage (" + p.linearisation.choice.method +
                                                "): --linearisation would apply a second one");
  linearise_image(linearisation_for_image(args), rgb.pixels.data(), rgb.pixels.size() / 3);  // linearise_option.hpp
  const std::string out_path = args.get("out");
  const auto t0 = std::chrono::steady_clock::now();
  const Image3f xyz = apply_profile(p, rgb.pixels.data(), rgb.width, rgb.height);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<uint8_t> bytes;
  const std::string e = ext_of(out_path);
  if (e == "tif" || e == "tiff") bytes = float_tiff(xyz.pixels.data(), xyz.width, xyz.height, "CIE XYZ (tristim " + p.model.id + ")");
  else if (e == "pfm") bytes = float_pfm(xyz.pixels.data(), xyz.width, xyz.height);
  else throw Error(ErrorCode::InvalidArgument, "--out must end in .tiff, .tif or .pfm");
  write_bytes(out_path, bytes.data(), bytes.size());
  std::cerr << "tristim apply: " << xyz.width << "x" << xyz.height << " in " << fmt(ms, 1) << " ms -> " << out_path << "\n";
  return 0;
}

const char* kExportUsage =
    "tristim export --profile p.json (--icc out.icc [--icc-version 4.3|2.4] [--grid 49] |\n"
    "               --cube out.cube [--size 33]) [--rgb-scale S]\n"
    "  ICC input profile (lcms2; matrix/shaper for 3×3 models, AToB0 LUT otherwise) or a .cube\n"
    "  (Resolve convention: 1D shaper u = d^(1/2.2), then a 3D LUT; read by Resolve and OpenColorIO).\n"
    "  Device value d = 1.0 = camera RGB S (default: the profile's largest training value).\n"
    "tristim export --profile p.json --dcp camera.dcp [--second p2.json] [--hue-sat-map 90,30,30]\n"
    "               (--camera-model \"<Make> <Model>\" | --raw photo.dng) [--illuminant D50] [--second-illuminant A]\n"
    "               [--profile-name T] [--copyright T] [--embed-policy allow-copying|embed-if-used|never|no-restrictions]\n"
    "               [--tone-curve linear] [--rgb-scale S]\n"
    "  DNG camera profile (Adobe DNG 1.6; Lightroom, Camera Raw, RawTherapee): ColorMatrix and ForwardMatrix from\n"
    "  the model (its linear part at neutral), with --second a dual-illuminant profile from a second profile of the\n"
    "  same camera under another illuminant, with --hue-sat-map a HueSatMap of hue,saturation,value divisions\n"
    "  carrying what a non-linear model adds. The calibration illuminant is the profile's reference illuminant\n"
    "  (--illuminant / --second-illuminant name it otherwise: A, F2, F11, D50, D55, D65, D75). The camera name\n"
    "  (UniqueCameraModel) comes from --camera-model or the RAW's make and model. `tristim inspect camera.dcp`\n"
    "  reads it back.";

int run_export(const Args& args, std::ostream& out) {
  if (args.has("dcp")) return run_export_dcp(args, out);  // cmd_dcp.cpp
  args.allow_only({"profile", "icc", "cube", "size", "grid", "rgb-scale", "icc-version"});
  const Profile p = profile_from_json(read_file(args.get("profile")));
  if (!args.has("icc") && !args.has("cube")) throw Error(ErrorCode::InvalidArgument, "export needs --icc, --cube or --dcp");
  const double scale = args.get_double("rgb-scale", 0);
  if (args.has("icc")) {
    IccOptions o;
    o.rgb_scale = scale;
    o.grid_points = static_cast<int>(args.get_double("grid", IccOptions{}.grid_points));
    o.version = args.get_double("icc-version", 4.3);
    const auto icc = export_icc(p, o);
    write_bytes(args.get("icc"), icc.data(), icc.size());
  }
  if (args.has("cube")) {
    const std::string cube = export_cube(p, static_cast<int>(args.get_double("size", 33)), scale);
    write_bytes(args.get("cube"), cube.data(), cube.size());
  }
  return 0;
}

int run_models(const Args& args, std::ostream& out) {
  args.allow_only({"json"});
  if (args.has("json")) {
    json::Value a = json::Value::array();
    for (const auto& m : model_table()) {
      json::Value o = json::Value::object();
      o.set("id", m.id);
      o.set("label", m.label);
      o.set("reference", m.reference);
      o.set("n_terms", m.n_terms);
      o.set("duplicate_of", m.duplicate_of);
      o.set("family", m.family);
      a.push(o);
    }
    out << a.dump(2) << "\n";
    return 0;
  }
  for (const auto& m : model_table())
    out << std::left << std::setw(18) << m.id << std::setw(4) << m.n_terms << m.label << " — " << m.reference
        << (m.duplicate_of.empty() ? "" : " (same as " + m.duplicate_of + ")") << "\n";
  return 0;
}

const CommandRegistration reg_eval({"evaluate", "evaluate a profile on test patches (JSON)", kEvaluateUsage, run_evaluate});
const CommandRegistration reg_cmp({"compare", "every model x objective, sorted by held-out error", kCompareUsage, run_compare,
                                   fit_methods_help});
const CommandRegistration reg_apply({"apply", "apply a profile to a linear image -> float XYZ TIFF/PFM", kApplyUsage, run_apply});
const CommandRegistration reg_export({"export", "export a profile as ICC, .cube or DNG camera profile (DCP)", kExportUsage, run_export});
const CommandRegistration reg_models({"models", "list the characterisation models", "tristim models [--json]", run_models});

}  // namespace
}  // namespace tristim::cli

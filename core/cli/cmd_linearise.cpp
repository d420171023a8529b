// CLI: `tristim linearise` (fit one linearisation, write linear per-patch values and, with
// --json, the curves and R²), `tristim spectral fit|apply` (Shen et al. 2008 eqs 26-28), and the
// `--linearisation` option other commands take (linearise_option.hpp).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "linearise_option.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/number.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/linearisation/spectral.hpp"
#include "tristim/profile/export.hpp"

namespace tristim::cli {

namespace {


std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw Error(ErrorCode::InvalidArgument, "cannot write '" + path + "'");
  f << text;
  if (!f) throw Error(ErrorCode::ExportFailed, "writing '" + path + "' failed");
}

void warn(const std::string& command, const Linearisation& l) {
  if (!l.message.empty()) std::cerr << "tristim " << command << ": warning: " << l.message << "\n";
}

SpectralData illuminant_of(const Args& args) { return illuminant_arg(args.get("illuminant", "D65")); }

Vec3 white_arg(const Args& args) {
  if (!args.has("ref-white")) return whites::D50();
  const std::string s = args.get("ref-white");
  if (s == "D50" || s == "d50") return whites::D50();
  if (s == "D65" || s == "d65") return whites::D65();
  std::vector<double> v;
  for (const auto& p : split_ids(s)) v.push_back(tristim::parse_double(p.c_str(), nullptr));
  if (v.size() != 3 || !(v[0] > 0 && v[1] > 0 && v[2] > 0))
    throw Error(ErrorCode::InvalidArgument, "--ref-white expects D50, D65 or X,Y,Z");
  return Vec3(v[0], v[1], v[2]);
}

/// Camera RGB and whatever reference the options give, paired by patch id (the RGB file's order).
/// `rgb` receives the RGB file's table: its labels are the ids the outputs write.
LinearisationData load_data(const Args& args, PatchTable& rgb) {
  const std::string rgb_path = args.get("rgb");
  rgb = read_patch_file(read_file(rgb_path), rgb_path);
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": needs R, G, B columns");
  LinearisationData d;
  d.ids = rgb.ids;
  d.camera_RGB.resize(static_cast<Eigen::Index>(rgb.ids.size()), 3);
  for (size_t i = 0; i < rgb.ids.size(); ++i) d.camera_RGB.row(static_cast<Eigen::Index>(i)) = rgb.RGB[i].transpose();
  if (args.has("xyz") && args.has("reflectances"))
    throw Error(ErrorCode::InvalidArgument, "give --reflectances or --xyz, not both");
  if (args.has("reflectances")) {
    d.reflectances = reflectances_arg(args.get("reflectances"));
    const SpectralData ill = illuminant_of(args);
    d.white = illuminant_white_XYZ(ill);
    d.reference_XYZ.resize(d.camera_RGB.rows(), 3);
    for (size_t i = 0; i < d.ids.size(); ++i)
      d.reference_XYZ.row(static_cast<Eigen::Index>(i)) =
          sd_to_XYZ(d.reflectances.wavelengths, d.reflectances.column(d.ids[i]), ill).transpose();
  }
  if (args.has("xyz")) {
    const std::string path = args.get("xyz");
    const PatchTable ref = read_patch_file(read_file(path), path);
    d.white = white_arg(args);
    if (!ref.has_XYZ && !ref.has_Lab) throw Error(ErrorCode::MissingColumn, path + ": needs X, Y, Z or L, a, b columns");
    d.reference_XYZ.resize(d.camera_RGB.rows(), 3);
    for (size_t i = 0; i < d.ids.size(); ++i) {
      size_t j = 0;
      while (j < ref.ids.size() && ref.ids[j] != d.ids[i]) ++j;
      if (j == ref.ids.size())
        throw Error(ErrorCode::PatchMismatch, "patch '" + rgb.labels[i] + "' of " + rgb_path + " is not in " + path);
      d.reference_XYZ.row(static_cast<Eigen::Index>(i)) =
          (ref.has_XYZ ? ref.XYZ[j] : Lab_to_XYZ(ref.Lab[j], d.white)).transpose();
    }
  }
  d.full_scale = args.has("full-scale") ? args.get_double("full-scale", 0) : default_full_scale(d.camera_RGB);
  if (!(d.full_scale > 0)) throw Error(ErrorCode::InvalidArgument, "--full-scale expects a positive number");
  return d;
}

/// --method (or --linearisation) with --grey, --J, --K, --L, --basis folded in.
MethodChoice choice_of(const Args& args, const std::string& key, LinearisationData& d) {
  MethodChoice c = parse_choice(args.get(key));
  if (args.has("grey")) {
    std::string joined;
    for (const auto& id : split_ids(args.get("grey"))) joined += (joined.empty() ? "" : ";") + id;
    c.settings["grey"] = joined;
  }
  for (const char* k : {"J", "K", "L"})
    if (args.has(k)) c.parameters[k] = args.get_double(k, 0);
  if (args.has("basis")) {
    const std::string b = args.get("basis");
    if (b == "munsell1269" || b == "patches") {
      c.settings["basis"] = b;
    } else {
      d.basis_reflectances = reflectances_arg(b);
      c.settings["basis"] = "user";
    }
  }
  return c;
}

/// The three channels' curves, 101 samples each: {"channel": "R", then CurveSamples' list}.
json::Value curves_json(const Linearisation& l) {
  json::Value a = json::Value::array();
  for (int c = 0; c < 3; ++c) {
    json::Value o = fields::object({{"channel", std::string(1, "RGB"[c])}});
    fields::write_members(sample_curve(l, c, 101), o);
    a.push(o);
  }
  return a;
}

// 17 significant digits: the values read back are the values computed. `ids`: as the input spelled them.
std::string linear_csv(const std::vector<std::string>& ids, const PatchMatrix& lin) {
  std::string out = "patch,R,G,B\n";
  char buf[96];
  for (Eigen::Index i = 0; i < lin.rows(); ++i) {
    std::snprintf(buf, sizeof buf, ",%.17g,%.17g,%.17g\n", lin(i, 0), lin(i, 1), lin(i, 2));
    out += ids[static_cast<size_t>(i)] + buf;
  }
  return out;
}

Linearisation read_fitted(const std::string& path) {
  const json::Value v = json::parse(read_file(path));
  if (const json::Value* inner = v.is_object() ? v.find("linearisation") : nullptr) return linearisation_from_json(*inner);
  return linearisation_from_json(v);
}

// ---- tristim linearise --------------------------------------------------------------------------

const char* kLineariseUsage =
    "tristim linearise --method <id>[:name=value,...] --rgb patches.csv\n"
    "                  [--reflectances spectra.csv|<chart id> [--illuminant D65] | --xyz reference.csv [--ref-white D50]]\n"
    "                  [--grey id,id,...] [--J 8 --K 2 --L 2] [--basis munsell1269|patches|set.csv]\n"
    "                  [--full-scale 255] [--out linear.csv] [--json]\n"
    "  Fits one linearisation (the inverse OECF per channel) and writes the linearised per-patch\n"
    "  values (the ids as --rgb spells them, columns R,G,B) to stdout or --out; with --json, stdout\n"
    "  gets the fitted curves (coefficients, 101 samples per channel over the fitted range, the\n"
    "  grey-based curve for Shen2008), R² per channel, the greys used and why, and the warnings\n"
    "  (also on stderr).\n"
    "  --json output loads back as --linearisation file.json (fit, compare, apply, spectral).\n"
    "  Methods: below (tristim linearise --list as JSON); Shen2008 needs --reflectances.\n"
    "  --full-scale: the encoding's largest value (default 1, 255 or 65535, whichever first holds\n"
    "  every value). --illuminant: for XYZ from reflectances (greys, colour targets). Values of\n"
    "  --xyz may be XYZ or L*a*b* (with --ref-white).";

int run_linearise(const Args& args, std::ostream& out) {
  args.allow_only({"method", "rgb", "reflectances", "xyz", "illuminant", "ref-white", "grey", "J", "K", "L", "basis",
                   "full-scale", "out", "json", "list"});
  if (args.has("list")) {
    // LinearisationListing's list (methods.hpp): the rows the page's catalog has, options as rows.
    out << fields::write(linearisation_listing()).dump(2) << "\n";
    return 0;
  }
  PatchTable rgb;
  LinearisationData d = load_data(args, rgb);
  const MethodChoice choice = choice_of(args, "method", d);
  const Linearisation l = fit_linearisation(choice, d);
  warn("linearise", l);
  const PatchMatrix lin = linearise(l, d.camera_RGB);
  const std::string csv = linear_csv(rgb.labels, lin);
  if (args.has("out")) write_text(args.get("out"), csv);
  if (args.has("json")) {
    Linearisation shown = l;  // the patches it names, as the RGB file spells them
    shown.fitted = patch_labels(rgb, l.fitted);
    shown.greys = patch_labels(rgb, l.greys);
    for (Extrapolation& e : shown.extrapolated) e.patch = patch_labels(rgb, {e.patch})[0];
    // A summary (Linearisation's own members, the message as "warnings"), the fitted linearisation, the curves.
    json::Value o = fields::write_picked(l, {"method", "full_scale", "r_squared", "monotonic"});
    o.set("warnings", l.message);
    o.set("linearisation", fields::write(shown));
    o.set("curves", curves_json(l));
    out << o.dump(2) << "\n";
  } else if (!args.has("out")) {
    out << csv;
  }
  return 0;
}

}  // namespace

// ---- the --linearisation option of other commands ------------------------------------------------

std::string linearisations_help() {
  std::vector<MethodInfo> rows;
  for (const auto& m : linearisation_table()) rows.push_back(m.info);
  return methods_help("Linearisations (--method, --linearisation; tristim linearise --list)", rows);
}

const std::vector<std::string>& linearisation_option_names() {
  static const std::vector<std::string> names{"linearisation", "reflectances", "full-scale"};
  return names;
}

double default_full_scale(const PatchMatrix& rgb) {
  const double m = rgb.size() ? rgb.maxCoeff() : 0;
  if (m <= 1) return 1;
  if (m <= 255) return 255;
  if (m <= 65535) return 65535;
  return m;
}

Linearisation linearisation_option(const Args& args, const std::string& command, const std::vector<std::string>& ids,
                                   PatchMatrix& rgb, const PatchMatrix& reference_XYZ, const Vec3& white) {
  LinearisationData d;
  d.ids = ids;
  d.camera_RGB = rgb;
  d.full_scale = args.has("full-scale") ? args.get_double("full-scale", 0) : default_full_scale(rgb);
  if (!args.has("linearisation")) return fit_linearisation(parse_choice("identity"), d);
  const std::string value = args.get("linearisation");
  Linearisation l;
  if (file_exists(value)) {
    l = read_fitted(value);
  } else {
    d.reference_XYZ = reference_XYZ;
    d.white = white;
    if (args.has("reflectances")) d.reflectances = reflectances_arg(args.get("reflectances"));
    l = fit_linearisation(parse_choice(value), d);
  }
  warn(command, l);
  rgb = linearise(l, rgb);
  return l;
}

Linearisation linearisation_for_image(const Args& args) {
  LinearisationData d;
  d.camera_RGB = PatchMatrix::Ones(1, 3);
  d.full_scale = args.get_double("full-scale", 255);
  if (!args.has("linearisation")) return fit_linearisation(parse_choice("identity"), d);
  const std::string value = args.get("linearisation");
  if (file_exists(value)) return read_fitted(value);
  const MethodChoice c = parse_choice(value);
  if (!linearisation_method(c.method).needs.empty())
    throw Error(ErrorCode::InvalidArgument, "--linearisation " + c.method +
                                                " is fitted to patches: pass the JSON written by `tristim linearise --json`");
  return fit_linearisation(c, d);
}

namespace {

// ---- tristim spectral fit | apply ------------------------------------------------------------------

const char* kSpectralUsage =
    "tristim spectral fit --rgb patches.csv --reflectances spectra.csv|<chart id>\n"
    "                     [--linearisation <id>[:options] | fitted.json] [--full-scale 255]\n"
    "                     [--use-greys] [--grey id;id;...] [--grey-threshold 2]\n"
    "                     [--illuminant D65] [--observer 1931] [--out model.json] [--csv estimates.csv]\n"
    "tristim spectral apply model.json --rgb patches.csv [--reflectances measured.csv] [--out estimates.csv] [--json]\n"
    "tristim spectral apply model.json <image.dng|image.pfm> --out bands.tiff\n"
    "  Spectral characterisation (Shen et al. 2008 eqs 26-28): W = [r][û]⁺ from linearised camera\n"
    "  RGB to reflectance, trained on the non-grey patches as the paper does (--use-greys: on every\n"
    "  patch; the greys by the Shen2008 linearisation's rule, options below). `fit` prints the model\n"
    "  JSON (training_set, training_patches, training_ids, greys) with every patch's spectral RMS\n"
    "  (eq 28) and CIEDE2000 of the estimated reflectances under --illuminant/--observer\n"
    "  (default D65, 1931), or writes it to --out; --csv writes the estimated reflectances.\n"
    "  `apply` writes estimated reflectances of patches (spectral CSV) — with --reflectances and\n"
    "  --json, their errors as JSON instead — or of an image as a multi-band 32-bit float TIFF\n"
    "  (one band per wavelength).";

/// The CLI flag of a catalog option: --name with '_' as '-' (use_greys -> --use-greys).
std::string flag_of(const OptionSpec& o) {
  std::string f = o.name;
  for (char& ch : f)
    if (ch == '_') ch = '-';
  return f;
}

/// The spectral characterisation's options (spectral_method()) from their flags.
MethodChoice spectral_options(const Args& args) {
  MethodChoice c;
  for (const OptionSpec& o : spectral_method().options) {
    const std::string f = flag_of(o);
    if (!args.has(f)) continue;
    if (o.type == "boolean") c.parameters[o.name] = 1;
    else if (o.type == "text" || o.type == "choice") c.settings[o.name] = args.get(f);
    else c.parameters[o.name] = args.get_double(f, o.default_number);
  }
  return c;
}

std::string spectral_help() {
  std::string s = "Spectral characterisation options (" + spectral_method().reference + "):\n";
  for (const OptionSpec& o : spectral_method().options) s += "  --" + flag_of(o) + ": " + o.description + "\n";
  return s + "\n" + linearisations_help();
}

/// Estimated reflectances with each column named as the patch file spells its id.
SpectralData labelled(SpectralData estimates, const PatchTable& table) {
  estimates.names = patch_labels(table, estimates.names);
  return estimates;
}

/// The errors as JSON (SpectralEvaluation's list), each patch named as `table` (the RGB file) spells it.
json::Value evaluation_json(SpectralEvaluation e, const PatchTable& table) {
  e.ids = patch_labels(table, e.ids);
  return fields::write(e);
}

int run_spectral(const Args& args, std::ostream& out) {
  if (args.positional.empty()) throw Error(ErrorCode::InvalidArgument, "usage: tristim spectral fit|apply ... (see --help)");
  const std::string what = args.positional[0];
  const Observer observer = parse_observer(args.get("observer", "1931"));
  if (what == "fit") {
    std::vector<std::string> allowed{"rgb", "reflectances", "linearisation", "full-scale", "illuminant", "observer", "out", "csv"};
    for (const OptionSpec& o : spectral_method().options) allowed.push_back(flag_of(o));
    args.allow_only(allowed);
    if (args.positional.size() != 1) throw Error(ErrorCode::InvalidArgument, "spectral fit takes no positional argument");
    PatchTable table;
    LinearisationData d = load_data(args, table);
    PatchMatrix rgb = d.camera_RGB;
    const Linearisation l = linearisation_option(args, "spectral", d.ids, rgb, d.reference_XYZ, d.white);
    if (d.reflectances.size() == 0) throw Error(ErrorCode::MissingColumn, "spectral fit needs --reflectances");
    const SpectralModel m = fit_spectral(l, d.ids, d.camera_RGB, d.reflectances, spectral_options(args));
    const SpectralEvaluation e = evaluate_spectral(m, d.ids, d.camera_RGB, d.reflectances, illuminant_of(args), observer);
    if (args.has("csv")) write_text(args.get("csv"), spectral_csv(labelled(estimate_reflectances(m, d.ids, d.camera_RGB), table)));
    json::Value o = spectral_model_json(m);
    o.set("training", evaluation_json(e, table));
    if (args.has("out")) {
      write_text(args.get("out"), o.dump(2) + "\n");
      std::cerr << "tristim spectral: W trained on " << m.training_patches << " of " << d.ids.size()
                << (m.training_set == "all" ? " patches (greys included)" : " patches, the non-grey ones")
                << "; every patch: spectral RMS mean " << e.rms_summary.mean
                << ", CIEDE2000 mean " << e.dE00_summary.mean << "\n";
    } else {
      out << o.dump(2) << "\n";
    }
    return 0;
  }
  if (what != "apply") throw Error(ErrorCode::InvalidArgument, "spectral: expected fit or apply, got '" + what + "'");
  args.allow_only({"rgb", "reflectances", "illuminant", "observer", "out", "json"});
  if (args.positional.size() < 2) throw Error(ErrorCode::InvalidArgument, "spectral apply needs the model JSON");
  const SpectralModel m = spectral_model_from_json(json::parse(read_file(args.positional[1])));
  if (args.positional.size() == 3) {  // an image
    const std::string path = args.positional[2], out_path = args.get("out");
    Image3f rgb;
    const auto dot = path.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    if (ext == "pfm" || ext == "PFM") {
      rgb = read_pfm(read_file(path));
    } else {
      const std::string bytes = read_file(path);
      RawImage raw = decode_raw(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      rgb.width = raw.width;
      rgb.height = raw.height;
      rgb.pixels = std::move(raw.rgb);
    }
    const size_t n = static_cast<size_t>(rgb.width) * static_cast<size_t>(rgb.height);
    std::vector<float> bands(n * m.wavelengths.size());
    estimate_reflectance_image(m, rgb.pixels.data(), n, bands.data());
    std::string desc = "reflectance (tristim spectral), bands at";
    for (double w : m.wavelengths) desc += " " + fmt(w);
    desc += " nm";
    const auto tiff = float_tiff_bands(bands.data(), rgb.width, rgb.height, static_cast<int>(m.wavelengths.size()), desc);
    std::ofstream f(out_path, std::ios::binary);
    if (!f) throw Error(ErrorCode::InvalidArgument, "cannot write '" + out_path + "'");
    f.write(reinterpret_cast<const char*>(tiff.data()), static_cast<std::streamsize>(tiff.size()));
    std::cerr << "tristim spectral: " << rgb.width << "x" << rgb.height << ", " << m.wavelengths.size() << " bands -> "
              << out_path << "\n";
    return 0;
  }
  const std::string rgb_path = args.get("rgb");
  const PatchTable t = read_patch_file(read_file(rgb_path), rgb_path);
  if (!t.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": needs R, G, B columns");
  PatchMatrix rgb(static_cast<Eigen::Index>(t.ids.size()), 3);
  for (size_t i = 0; i < t.ids.size(); ++i) rgb.row(static_cast<Eigen::Index>(i)) = t.RGB[i].transpose();
  const SpectralData est = labelled(estimate_reflectances(m, t.ids, rgb), t);
  if (args.has("json")) {
    if (!args.has("reflectances")) throw Error(ErrorCode::InvalidArgument, "spectral apply --json needs --reflectances");
    const SpectralData measured = reflectances_arg(args.get("reflectances"));
    out << evaluation_json(evaluate_spectral(m, t.ids, rgb, measured, illuminant_of(args), observer), t).dump(2) << "\n";
    if (args.has("out")) write_text(args.get("out"), spectral_csv(est));
    return 0;
  }
  if (args.has("out")) write_text(args.get("out"), spectral_csv(est));
  else out << spectral_csv(est);
  return 0;
}

const CommandRegistration reg_linearise({"linearise", "fit a linearisation (inverse OECF) -> linear patches CSV / JSON",
                                         kLineariseUsage, run_linearise, linearisations_help});
const CommandRegistration reg_spectral({"spectral", "spectral characterisation: fit W, estimate reflectances",
                                        kSpectralUsage, run_spectral, spectral_help});

}  // namespace
}  // namespace tristim::cli

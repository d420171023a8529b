// CLI: surface — fit a surface correction between two measurements of the same patches (Abed,
// Berns & Masaoka 2013 Phase I), list the presets and methods. CSV (default) or JSON on stdout.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>

#include "cli.hpp"
#include "tristim/error.hpp"
#include "tristim/io/json.hpp"
#include "tristim/number.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/geometry_table.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/options_table.hpp"
#include "tristim/surface/saunderson.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim::cli {

namespace {

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

/// A spectral patch file (its spectra: t.spectra, columns named by the normalised ids; t.labels:
/// the ids as the file spells them, for the output).
PatchTable read_reflectances(const std::string& path) {
  PatchTable t = read_patch_file(read_file(path), path);
  if (!t.has_spectra)
    throw Error(ErrorCode::MissingColumn, path + ": no spectral data (a wavelength_nm column and one column per patch)");
  return t;
}

SpectralData illuminant_of(const std::string& value) {
  if (std::ifstream(value)) {
    SpectralData d = read_spectral_csv(read_file(value), value);
    d.values.resize(1);
    d.names.resize(1);
    return d;
  }
  return illuminant_spd(value);
}

/// "400-700" -> {400, 700}.
void parse_range(const std::string& text, double& lo, double& hi) {
  const auto dash = text.find('-', 1);
  char* end1 = nullptr;
  char* end2 = nullptr;
  if (dash != std::string::npos) {
    const std::string a = text.substr(0, dash), b = text.substr(dash + 1);
    lo = tristim::parse_double(a.c_str(), &end1);
    hi = tristim::parse_double(b.c_str(), &end2);
    if (!a.empty() && !b.empty() && *end1 == '\0' && *end2 == '\0' && hi > lo && lo > 0) return;
  }
  throw Error(ErrorCode::InvalidArgument, "--range expects start-end in nm, e.g. 400-700, got '" + text + "'");
}

// Start values: --start choice text, else the method with the Saunderson geometries of
// --measurement / --capture presets (defaults d8-sci -> 45-0).
MethodChoice start_choice(const Args& args) {
  const std::string method = args.get("method");
  MethodChoice c = args.has("start") ? parse_choice(args.get("start")) : MethodChoice{method, {}, {}};
  if (c.method != method)
    throw Error(ErrorCode::InvalidArgument, "--start names method '" + c.method + "' but --method is '" + method + "'");
  if (method == "saunderson") {
    const SaundersonGeometry m = saunderson_preset(args.get("measurement", "d8-sci")).geometry;
    const SaundersonGeometry k = saunderson_preset(args.get("capture", "45-0")).geometry;
    const std::pair<const char*, double> given[] = {{"k1", m.k1}, {"k2", m.k2}, {"k_ins", m.k_ins},
                                                     {"k1_capture", k.k1}, {"k2_capture", k.k2}, {"k_ins_capture", k.k_ins}};
    for (const auto& [name, value] : given)
      if (!c.parameters.count(name)) c.parameters[name] = value;
  } else if (args.has("measurement") || args.has("capture")) {
    throw Error(ErrorCode::InvalidArgument, "--measurement / --capture presets apply to --method saunderson only");
  }
  return c;
}

int run_fit(const Args& args, std::ostream& out) {
  args.allow_only({"from", "to", "method", "range", "illuminant", "observer", "json", "start", "measurement",
                   "capture", "free", "per-wavelength"});
  const std::string from = args.get("from"), to = args.get("to");
  SurfaceFitOptions o;
  if (args.has("range")) parse_range(args.get("range"), o.range_min, o.range_max);
  const std::string illuminant = args.get("illuminant", "D50");
  o.illuminant = illuminant_of(illuminant);
  o.observer = parse_observer(args.get("observer", "1931"));
  o.free = args.get("free", "capture");
  o.per_wavelength = args.has("per-wavelength");
  const MethodChoice start = start_choice(args);
  const PatchTable measured = read_reflectances(from);
  const SurfaceFitResult r = fit_surface(start, measured.spectra, read_reflectances(to).spectra, o);
  const std::vector<std::string> ids = patch_labels(measured, r.ids);  // as --from spells them
  const double lo = r.wavelengths.front(), hi = r.wavelengths.back();
  if (args.has("json")) {  // the result's field list (fit.hpp): patches as --from spells them, no spectra
    SurfaceFitResult printed = r;
    printed.ids = ids;
    printed.illuminant = illuminant;
    printed.measured = printed.corrected = printed.target = SpectralData{};
    out << fields::write(printed).dump(2) << "\n";
    return 0;
  }
  out << "# tristim surface fit: " << r.choice.method << ", " << r.ids.size() << " patches, " << fixed(lo, 0) << "-"
      << fixed(hi, 0) << " nm (" << r.wavelengths.size() << " wavelengths), " << illuminant << ", "
      << observer_name(o.observer) << "\n";
  out << "# surface: " << surface_choice_text(r.choice) << "\n";
  out << "# status: " << r.status << (r.message.empty() ? "" : " (" + r.message + ")") << "\n";
  out << "# spectral RMS: before " << fixed(r.spectral_rms_before, 6) << ", after " << fixed(r.spectral_rms_after, 6)
      << "\n";
  out << "# CIEDE2000: before mean " << fixed(r.summary_dE00_before.mean, 3) << " max "
      << fixed(r.summary_dE00_before.max, 3) << ", after mean " << fixed(r.summary_dE00_after.mean, 3) << " max "
      << fixed(r.summary_dE00_after.max, 3) << "\n";
  out << "patch,rms_before,rms_after,dE00_before,dE00_after\n";
  for (size_t i = 0; i < r.ids.size(); ++i)
    out << ids[i] << ',' << fixed(r.rms_before[i], 6) << ',' << fixed(r.rms_after[i], 6) << ','
        << fixed(r.dE00_before[i], 4) << ',' << fixed(r.dE00_after[i], 4) << '\n';
  return 0;
}

/// "r,g,b" -> Vec3.
Vec3 parse_triplet(const std::string& key, const std::string& text) {
  Vec3 v;
  size_t pos = 0;
  for (int c = 0; c < 3; ++c) {
    const size_t end = c < 2 ? text.find(',', pos) : text.size();
    const std::string item = end == std::string::npos ? "" : text.substr(pos, end - pos);
    char* stop = nullptr;
    v[c] = tristim::parse_double(item.c_str(), &stop);
    if (item.empty() || *stop != '\0') throw Error(ErrorCode::InvalidArgument, "--" + key + " expects R,G,B, got '" + text + "'");
    pos = end + 1;
  }
  return v;
}

std::string matrix_text(const Mat3& m) {
  std::string s;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s += (r || c ? (c ? "," : ";") : "") + json::number_text(m(r, c));
  return s;
}

int run_joint(const Args& args, std::ostream& out) {
  args.allow_only({"rgb", "reflectances", "method", "illuminant", "observer", "white-rgb", "white-reflectance",
                   "start", "measurement", "capture", "free", "json"});
  const std::string rgb_path = args.get("rgb"), refl_path = args.get("reflectances");
  const PatchTable rgb = read_patch_file(read_file(rgb_path), rgb_path);
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": needs R, G, B columns");
  const SpectralData refl = read_reflectances(refl_path).spectra;
  // Pair by id: the RGB file's patches, in its order, each needing a spectrum.
  SpectralData paired;
  paired.wavelengths = refl.wavelengths;
  paired.linear = refl.linear;
  PatchMatrix camera_RGB(static_cast<Eigen::Index>(rgb.ids.size()), 3);
  std::string missing;
  for (size_t i = 0; i < rgb.ids.size(); ++i) {
    size_t k = 0;
    while (k < refl.names.size() && normalise_patch_id(refl.names[k]) != rgb.ids[i]) ++k;
    if (k == refl.names.size()) { missing += (missing.empty() ? "" : ", ") + rgb.labels[i]; continue; }
    camera_RGB.row(static_cast<Eigen::Index>(paired.size())) = rgb.RGB[i].transpose();
    paired.names.push_back(rgb.ids[i]);
    paired.values.push_back(refl.values[k]);
  }
  if (!missing.empty())
    throw Error(ErrorCode::PatchMismatch, refl_path + " has no spectrum for patch(es) " + missing + " of " + rgb_path);
  JointFitOptions o;
  o.illuminant = illuminant_of(args.get("illuminant", "D50"));
  o.observer = parse_observer(args.get("observer", "1931"));
  o.white_RGB = parse_triplet("white-rgb", args.get("white-rgb"));
  o.white_reflectance = args.get_double("white-reflectance", 1.0);
  o.free = args.get("free", "capture");
  const JointFitResult r = fit_surface_joint_Abed2013(start_choice(args), camera_RGB, paired, o);
  if (args.has("json")) {  // the result's field list (joint.hpp)
    out << fields::write(r).dump(2) << "\n";
    return 0;
  }
  out << "key,value\nsurface," << surface_choice_text(r.choice) << "\nmatrix,\"" << matrix_text(r.matrix)
      << "\"\ndE_xyz_rms_start," << fixed(r.dE_xyz_rms_start, 6) << "\ndE_xyz_rms," << fixed(r.dE_xyz_rms, 6)
      << "\nstatus," << r.status << "\n";
  return 0;
}

int run_table4(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "illuminant", "noise", "seed", "json"});
  const double seed = args.get_double("seed", 1);
  if (!(seed >= 0) || seed != static_cast<double>(static_cast<uint64_t>(seed)))
    throw Error(ErrorCode::InvalidArgument, "--seed expects a non-negative integer");
  const double noise = args.get_double("noise", 0.001);  // bounds: the noise row of surface_option_table()
  const GeometryExperiment x = geometry_experiment_Abed2013(args.get("camera", "Nikon_D850"), args.get("illuminant", "D50"),
                                                            noise, static_cast<uint64_t>(seed));
  const auto cells = geometry_table_Abed2013(x.training, x.test, x.options);
  if (args.has("json")) {  // each cell by its field list (geometry_table.hpp)
    out << fields::object({{"test", x.test.name}, {"cells", fields::write(cells)}}).dump(2) << "\n";
    return 0;
  }
  out << "training,method,dE_xyz_mean,dE_xyz_max,dE00_mean,dE00_max,status\n";
  for (const auto& c : cells)
    out << c.training << ',' << c.method << ',' << fixed(c.dE_xyz.mean, 4) << ',' << fixed(c.dE_xyz.max, 4) << ','
        << fixed(c.dE00.mean, 2) << ',' << fixed(c.dE00.max, 2) << ',' << (c.ok ? (c.status.empty() ? "ok" : c.status) : c.error_code)
        << '\n';
  return 0;
}

int run_presets(const Args& args, std::ostream& out) {
  args.allow_only({});
  out << "id,role,k1,k2,k_ins,label,source\n";
  for (const auto& p : saunderson_presets())
    out << p.id << ',' << p.role << ',' << p.geometry.k1 << ',' << p.geometry.k2 << ',' << p.geometry.k_ins << ",\""
        << p.label << "\",\"" << p.source << "\"\n";
  return 0;
}

int run_methods(const Args& args, std::ostream& out) {
  args.allow_only({});
  out << "id,coefficients,label,reference\n";
  for (const auto& m : surface_table()) {
    std::string c;
    for (const auto& name : m.coefficients) c += (c.empty() ? "" : ";") + name;
    out << m.info.id << ',' << c << ",\"" << m.info.label << "\",\"" << m.info.reference << "\"\n";
  }
  return 0;
}

int run_surface(const Args& args, std::ostream& out) {
  const std::string sub = args.positional.empty() ? "" : args.positional[0];
  if (args.positional.size() > 1)
    throw Error(ErrorCode::InvalidArgument, "unexpected argument '" + args.positional[1] + "'");
  if (sub == "fit") return run_fit(args, out);
  if (sub == "joint") return run_joint(args, out);
  if (sub == "table4") return run_table4(args, out);
  if (sub == "presets") return run_presets(args, out);
  if (sub == "methods") return run_methods(args, out);
  throw Error(ErrorCode::InvalidArgument, "tristim surface needs a subcommand: fit, joint, table4, presets or methods (got '" + sub + "')");
}

CommandRegistration reg_surface(
    {"surface", "surface correction between measurement geometries (Abed 2013): fit, joint, table4, presets, methods",
     "tristim surface fit --from measured.csv --to target.csv --method saunderson|scaler-offset|scaler|offset|none\n"
     "                    [--range 400-700] [--illuminant D50] [--observer 1931] [--json]\n"
     "                    [--measurement d8-sci] [--capture 45-0] [--start <method>:<name>=<value>,...]\n"
     "                    [--free capture|measurement|k1_capture+...] [--per-wavelength]\n"
     "  Phase I of Abed, Berns & Masaoka (2013): the coefficients that map the reflectances of --from onto\n"
     "  another measurement of the same patches (--to) in another geometry, minimising the spectral RMS\n"
     "  (bounded NLopt BOBYQA). Spectral CSV: a wavelength_nm column, one column per patch, paired by name\n"
     "  (A01 = A1). --range defaults to the overlap of the two sets. Saunderson keeps the instrument\n"
     "  (--measurement preset) fixed and fits the capture coefficients (--capture preset = start values);\n"
     "  --free all is refused (ILL_POSED: eq 3 has only three independent parameters, eq 4).\n"
     "  Prints '# ' lines (the fitted correction as a --surface value, status, spectral RMS and CIEDE2000\n"
     "  before/after) then CSV patch,rms_before,rms_after,dE00_before,dE00_after; --json prints everything.\n"
     "tristim surface joint --rgb patches.csv --reflectances spectra.csv --white-rgb R,G,B --method <m>\n"
     "                    [--white-reflectance 1] [--illuminant D50] [--observer 1931] [--measurement d8-sci]\n"
     "                    [--capture 45-0] [--start ...] [--free capture] [--json]\n"
     "  Phase II (Figure 3): the correction jointly with a 3x3 matrix, minimising dE_xyz; the matrix maps the\n"
     "  white reference's camera RGB (--white-rgb, a Lambertian white such as PTFE in the capture geometry)\n"
     "  to --white-reflectance times the illuminant's white exactly (the anchor against the scale\n"
     "  degeneracy). Prints the fitted --surface value and the matrix.\n"
     "tristim surface table4 [--camera Nikon_D850] [--illuminant D50] [--noise 0.001] [--seed 1] [--json]\n"
     "  Table IV by simulation: training charts (Classic, SG, Glossy, Total) rendered with the paper's Table III\n"
     "  coefficients (instrument 45:0, capture diffuse booth) by the virtual camera, five methods, tested on\n"
     "  a matte CC24 seen in the capture geometry; dE_xyz with the white at Y = 1.\n"
     "tristim surface presets    Saunderson coefficients of common geometries, with their sources (CSV)\n"
     "tristim surface methods    the surface-correction table (CSV)\n"
     "Apply a correction to a chart's reference: tristim reference --chart sg140 --surface <value of '# surface:'>",
     run_surface, [] {
       std::vector<MethodInfo> rows;
       for (const auto& m : surface_table()) rows.push_back(m.info);
       return methods_help("Surface corrections (--method; tristim surface methods)", rows) +
              option_rows_help("Numbers (the page's boxes; fit --range min-max in nm, table4 --noise)",
                               surface_option_table());
     }});

}  // namespace

}  // namespace tristim::cli

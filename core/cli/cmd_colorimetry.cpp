// CLI: reference, difference, simulate, list — colorimetry from the command line, CSV on stdout.
#include <cstdio>
#include <fstream>
#include <ostream>
#include <string>

#include "cli.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"
#include "tristim/number.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/methods.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim::cli {

namespace {

int g_significant = 0;  // --precision N: print N significant digits (%.Ng) instead of fixed decimals

std::string num(double v, int decimals = 6) {
  char buf[64];
  if (g_significant > 0) {
    std::snprintf(buf, sizeof buf, "%.*g", g_significant, v);
    return buf;
  }
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s(buf);
  if (s == "-0.000000") s = "0.000000";
  return s;
}

void set_precision(const Args& args) {
  if (!args.has("precision")) return;
  const double p = args.get_double("precision", 0);
  if (!(p >= 1 && p <= 17) || p != static_cast<int>(p))
    throw Error(ErrorCode::InvalidArgument, "--precision expects 1..17 significant digits");
  g_significant = static_cast<int>(p);
}

int run_reference(const Args& args, std::ostream& out) {
  args.allow_only({"chart", "illuminant", "observer", "precision", "surface"});
  set_precision(args);
  const std::string chart = args.get("chart");
  const Observer observer = parse_observer(args.get("observer", "1931"));
  SpectralData reflectances = chart_reflectances(chart);
  if (args.has("surface")) reflectances = correct_surface(parse_choice(args.get("surface")), reflectances);
  const ReferenceChart r = reference_from_spectra(reflectances, illuminant_arg(args.get("illuminant", "D65")), observer);
  out << "patch,X,Y,Z,L,a,b\n";
  for (size_t i = 0; i < r.ids.size(); ++i)
    out << r.ids[i] << ',' << num(r.XYZ[i][0]) << ',' << num(r.XYZ[i][1]) << ',' << num(r.XYZ[i][2]) << ',' << num(r.Lab[i][0])
        << ',' << num(r.Lab[i][1]) << ',' << num(r.Lab[i][2]) << '\n';
  return 0;
}

int run_difference(const Args& args, std::ostream& out) {
  args.allow_only({"method", "in"});
  const std::string method = args.get("method", "CIE2000");
  if (method != "CIE2000" && method != "CIE1994" && method != "CIE1976")
    throw Error(ErrorCode::UnknownId, "unknown --method '" + method + "' (use CIE2000, CIE1994 or CIE1976)");
  const std::string path = args.get("in");
  const TextTable t = parse_delimited(read_file(path), path);
  const char* names[6] = {"L1", "a1", "b1", "L2", "a2", "b2"};
  int col[6];
  for (int k = 0; k < 6; ++k) {
    col[k] = t.find({names[k]});
    if (col[k] < 0)
      throw Error(ErrorCode::MissingColumn, path + ", line " + std::to_string(t.header_line) + ": no column '" + names[k] +
                                                "' (need L1,a1,b1,L2,a2,b2)");
  }
  for (size_t k = 0; k < t.header.size(); ++k) out << t.header[k] << ',';
  out << "dE\n";
  for (size_t r = 0; r < t.rows.size(); ++r) {
    double v[6];
    for (int k = 0; k < 6; ++k) v[k] = parse_cell(t.rows[r][col[k]], path, t.lines[r], names[k]);
    const Vec3 Lab1(v[0], v[1], v[2]), Lab2(v[3], v[4], v[5]);
    const double dE = method == "CIE2000"   ? delta_E_CIE2000(Lab1, Lab2)
                      : method == "CIE1994" ? delta_E_CIE1994(Lab1, Lab2)
                                            : delta_E_CIE1976(Lab1, Lab2);
    for (const auto& cell : t.rows[r]) out << (cell.find(',') != std::string::npos ? "\"" + cell + "\"" : cell) << ',';
    out << num(dE) << '\n';
  }
  return 0;
}

/// "gamma=1.8,scale=22[,max=255]"
void parse_oecf(const std::string& spec, SimulationOptions& o) {
  o.oecf = true;
  size_t pos = 0;
  while (pos <= spec.size()) {
    const size_t end = std::min(spec.find(',', pos), spec.size());
    const std::string item = spec.substr(pos, end - pos);
    const size_t eq = item.find('=');
    if (eq == std::string::npos) throw Error(ErrorCode::InvalidArgument, "--oecf expects gamma=G,scale=L[,max=M], got '" + spec + "'");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    char* e = nullptr;
    const double v = tristim::parse_double(value.c_str(), &e);
    if (value.empty() || *e != '\0' || !(v > 0))
      throw Error(ErrorCode::InvalidArgument, "--oecf: '" + key + "' needs a positive number, got '" + value + "'");
    if (key == "gamma") o.oecf_gamma = v;
    else if (key == "scale" || key == "l") o.oecf_scale = v;
    else if (key == "max") o.clip_max = v;
    else throw Error(ErrorCode::InvalidArgument, "--oecf: unknown key '" + key + "' (gamma, scale, max)");
    pos = end + 1;
  }
}

int run_simulate(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "reflectances", "illuminant", "noise", "seed", "oecf", "white", "levels", "precision"});
  set_precision(args);
  const std::string cam = args.get("camera");
  const SpectralData ssf = file_exists(cam) ? read_ssf_csv(read_file(cam), cam) : camera_ssf(cam);
  const std::string refl = args.get("reflectances");
  const SpectralData reflectances = reflectances_arg(refl);
  const SpectralData ill = illuminant_arg(args.get("illuminant", "D65"));
  SimulationOptions o;
  o.white_level = args.get_double("white", 1.0);
  o.noise_sigma = args.get_double("noise", 0.0);
  const double seed = args.get_double("seed", 1.0);
  if (seed < 0 || seed != static_cast<double>(static_cast<uint64_t>(seed)))
    throw Error(ErrorCode::InvalidArgument, "--seed expects a non-negative integer");
  o.seed = static_cast<uint64_t>(seed);
  if (args.has("oecf")) parse_oecf(args.get("oecf"), o);
  if (args.has("levels")) {
    o.clip_max = args.get_double("levels", 0);
    if (!(o.clip_max > 0)) throw Error(ErrorCode::InvalidArgument, "--levels expects a positive number");
    o.quantise = true;
  }
  const auto rgb = simulate_camera_RGB(ssf, reflectances, ill, o);
  const std::vector<std::string> ids = reflectance_labels(refl, reflectances.names);  // as the file spells them
  out << "patch,R,G,B\n";
  const int decimals = o.quantise ? 0 : 8;
  for (size_t i = 0; i < rgb.size(); ++i)
    out << ids[i] << ',' << num(rgb[i][0], decimals) << ',' << num(rgb[i][1], decimals) << ','
        << num(rgb[i][2], decimals) << '\n';
  return 0;
}

int run_list(const Args& args, std::ostream& out) {
  args.allow_only({"what"});
  const std::string what = args.get("what", "all");
  if (what != "all" && what != "charts" && what != "illuminants" && what != "cameras" && what != "observers")
    throw Error(ErrorCode::UnknownId, "unknown --what '" + what + "' (charts, illuminants, cameras, observers)");
  out << "kind,id,description\n";
  if (what == "all" || what == "charts")
    for (const auto& c : list_charts()) out << "chart," << c.id << ",\"" << c.name << "\"\n";
  if (what == "all" || what == "illuminants")
    for (const auto& i : illuminant_ids()) out << "illuminant," << i << ",CIE\n";
  if (what == "all" || what == "observers") out << "observer,1931,CIE 1931 2°\nobserver,1964,CIE 1964 10°\n";
  if (what == "all" || what == "cameras")
    for (const auto& c : camera_names()) out << "camera," << c << ",rawtoaces-data\n";
  return 0;
}

CommandRegistration reg_reference({"reference", "reference XYZ and Lab of a built-in chart (CSV)",
                                   "tristim reference --chart <cc24|cc24-2005|sg140|sg140-2005|passport>\n"
                                   "                  [--illuminant D65|A|D50|D55|D75|E|F2|F11|D<CCT>|spd.csv] [--observer 1931|1964]\n"
                                   "Prints CSV patch,X,Y,Z,L,a,b: XYZ with the perfect diffuser at Y = 100, Lab relative to the\n"
                                   "illuminant's white; computed from the chart's spectra (1 nm integration, CIE 15).\n"
                                   "--precision 17 prints every number with 17 significant digits (round-trip exact).\n"
                                   "--surface <method>:<name>=<value>,... corrects the chart's reflectances for the capture\n"
                                   "geometry first (Abed 2013; `tristim surface methods`, or the '# surface:' line of\n"
                                   "`tristim surface fit`), e.g. --surface scaler-offset:mu=0.98,rho=-0.012",
                                   run_reference});
CommandRegistration reg_difference({"difference", "colour differences of Lab pairs (CSV)",
                                    "tristim difference [--method CIE2000|CIE1994|CIE1976] --in pairs.csv\n"
                                    "pairs.csv has columns L1,a1,b1,L2,a2,b2 (others are copied); prints the rows plus dE.",
                                    run_difference});
CommandRegistration reg_simulate({"simulate", "virtual camera: RGB of reflectances through camera sensitivities (CSV)",
                                  "tristim simulate --camera <name|ssf.csv> --reflectances <chart id|spectral.csv>\n"
                                  "                 [--illuminant D65|...|spd.csv] [--white 1] [--noise sigma --seed n]\n"
                                  "                 [--oecf gamma=1.8,scale=22[,max=255]] [--levels 255]\n"
                                  "Prints CSV patch,R,G,B. Linear RGB has the perfect diffuser at G = --white; --oecf applies\n"
                                  "Shen et al. (2008) eq 29 rho = scale*u^(1/gamma); --noise adds seeded Gaussian noise (after the\n"
                                  "OECF if any); --levels clips to [0, levels] and rounds. `tristim list --what cameras` lists cameras.",
                                  run_simulate});
CommandRegistration reg_list({"list", "built-in charts, illuminants, observers and cameras (CSV)",
                              "tristim list [--what all|charts|illuminants|observers|cameras]", run_list});

}  // namespace

}  // namespace tristim::cli

// CLI helpers shared by the model commands (fit, evaluate, compare, apply, export): patch tables
// paired by id, white points, fit options from flags, output files.
#include "patch_args.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "linearise_option.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/number.hpp"
#include "tristim/io/patch_files.hpp"

namespace tristim::cli {

// ---- patch tables -----------------------------------------------------------------------
// Read with the shared readers (tristim/io/patch_files.hpp: CSV or CGATS) and paired by id
// strictly: every patch of one file must be in the other. Pairing uses the normalised ids and
// keeps the RGB file's order (pair_by_id, the page's pairing too); what the commands write uses
// the ids as the user's file spells them (PatchTable::labels).

Vec3 parse_white(const Args& args, const std::string& key, const Vec3& fallback) {
  if (!args.has(key)) return fallback;
  const std::string s = args.get(key);
  std::string l = s;
  for (auto& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (l == "d50") return whites::D50();
  if (l == "d65") return whites::D65();
  std::vector<std::string> parts;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) parts.push_back(item);
  if (parts.size() != 3) throw Error(ErrorCode::InvalidArgument, "--" + key + " expects D50, D65 or X,Y,Z");
  Vec3 w;
  for (int c = 0; c < 3; ++c) {
    char* end = nullptr;
    w[c] = tristim::parse_double(parts[c].c_str(), &end);
    if (parts[c].empty() || *end != '\0' || !(w[c] > 0))
      throw Error(ErrorCode::InvalidArgument, "--" + key + ": '" + parts[c] + "' is not a positive number");
  }
  return w;
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto b = item.find_first_not_of(' '), e = item.find_last_not_of(' ');
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

PatchMatrix to_matrix(const std::vector<Vec3>& v) {
  PatchMatrix m(v.size(), 3);
  for (size_t i = 0; i < v.size(); ++i) m.row(i) = v[i].transpose();
  return m;
}

// Pairs camera RGB with reference XYZ (or L*a*b*, converted with ref_white) by patch id.
PatchData load_pairs(const std::string& rgb_path, const std::string& xyz_path, const Vec3& ref_white, bool subset) {
  const PatchTable rgb = read_patch_file(read_file(rgb_path), rgb_path);
  const PatchTable ref = read_patch_file(read_file(xyz_path), xyz_path);
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": needs R, G, B columns");
  std::vector<Vec3> ref_xyz;
  if (ref.has_XYZ) {
    ref_xyz = ref.XYZ;
  } else if (ref.has_Lab) {
    for (const auto& lab : ref.Lab) ref_xyz.push_back(Lab_to_XYZ(lab, ref_white));
  } else {
    throw Error(ErrorCode::MissingColumn, xyz_path + ": needs X, Y, Z or L, a, b columns");
  }
  if (!subset && rgb.ids.size() != ref.ids.size())
    throw Error(ErrorCode::PatchMismatch, rgb_path + " has " + std::to_string(rgb.ids.size()) + " patches but " +
                                              xyz_path + " has " + std::to_string(ref.ids.size()));
  PatchPairs pairs;
  try {
    pairs = pair_by_id(ref.ids, ref_xyz, rgb.ids, rgb.RGB);
  } catch (const Error& e) {  // no id shared: once the lengths may differ, this is where the files part
    if (!subset) throw;
    throw Error(e.code(), rgb_path + " and " + xyz_path + ": " + e.what());
  }
  if (!subset && !pairs.missing_in_measured.empty())
    throw Error(ErrorCode::PatchMismatch, "patch '" + patch_labels(ref, {pairs.missing_in_measured.front()}).front() +
                                              "' of " + xyz_path + " is not in " + rgb_path);
  if (!pairs.missing_in_reference.empty())
    throw Error(ErrorCode::PatchMismatch, "patch '" + patch_labels(rgb, {pairs.missing_in_reference.front()}).front() +
                                              "' of " + rgb_path + " is not in " + xyz_path);
  PatchData d;
  d.without_rgb = patch_labels(ref, pairs.missing_in_measured);
  d.ids = pairs.ids;
  d.labels = patch_labels(rgb, pairs.ids);
  d.rgb = to_matrix(pairs.measured);
  d.xyz = to_matrix(pairs.reference);
  return d;
}

PatchData load_pairs(const Args& args, const Vec3& ref_white, bool subset) {
  const std::vector<std::string> rgb = args.all("rgb"), xyz = args.all("xyz");
  if (rgb.size() != xyz.size())
    throw Error(ErrorCode::InvalidArgument, "--rgb and --xyz: " + std::to_string(rgb.size()) + " camera tables but " +
                                                std::to_string(xyz.size()) +
                                                " reference tables (one --xyz per --rgb, in the same order)");
  if (rgb.size() <= 1) return load_pairs(args.get("rgb"), args.get("xyz"), ref_white, subset);
  PatchData d;
  std::vector<Vec3> all_rgb, all_xyz;
  for (size_t k = 0; k < rgb.size(); ++k) {
    const PatchData one = load_pairs(rgb[k], xyz[k], ref_white, subset);
    const std::string prefix = std::to_string(k + 1) + ":";
    for (const auto& id : one.without_rgb) d.without_rgb.push_back(prefix + id);
    for (size_t i = 0; i < one.ids.size(); ++i) {
      d.ids.push_back(prefix + one.ids[i]);
      d.labels.push_back(prefix + one.labels[i]);
      all_rgb.push_back(one.rgb.row(static_cast<Eigen::Index>(i)).transpose());
      all_xyz.push_back(one.xyz.row(static_cast<Eigen::Index>(i)).transpose());
    }
  }
  d.rgb = to_matrix(all_rgb);
  d.xyz = to_matrix(all_xyz);
  return d;
}

std::string without_rgb_note(const std::string& command, const std::string& done, const PatchData& d) {
  if (d.without_rgb.empty()) return "";
  std::string s = "tristim " + command + ": " + std::to_string(d.without_rgb.size()) + " reference patches have no RGB (";
  for (size_t i = 0; i < d.without_rgb.size(); ++i) s += (i ? ", " : "") + d.without_rgb[i];
  return s + "): " + done + " on the " + std::to_string(d.ids.size()) + " others\n";
}

std::string read_files(const std::vector<std::string>& paths) {
  std::string all;
  for (const auto& p : paths) all += read_file(p);
  return all;
}

std::string per_chart_figures(const Args& args, const std::vector<std::string>& labels, const ModelEvaluation& ev) {
  const std::vector<std::string> names = args.all("rgb");
  if (names.size() < 2) return "";
  std::ostringstream o;
  for (size_t k = 0; k < names.size(); ++k) {
    const std::string prefix = std::to_string(k + 1) + ":";
    std::vector<double> train, loo;
    for (size_t i = 0; i < labels.size(); ++i)
      if (labels[i].compare(0, prefix.size(), prefix) == 0) {
        train.push_back(ev.training.patches.dE00[i]);
        if (ev.has_loo) loo.push_back(ev.loo.patches.dE00[i]);
      }
    if (train.empty()) continue;
    const Summary t = summarize(train);
    o << "tristim: chart " << k + 1 << " (" << names[k] << "): " << train.size() << " patches, training mean/max dE00 "
      << fmt(t.mean) << "/" << fmt(t.max);
    if (ev.has_loo) {
      const Summary l = summarize(loo);
      o << ", leave-one-out mean/max dE00 " << fmt(l.mean) << "/" << fmt(l.max);
    }
    o << "\n";
  }
  return o.str();
}

std::string chart_figures_text(const std::vector<ChartFigures>& charts) {
  std::ostringstream o;
  const auto pair = [](const Summary& s) { return fmt(s.mean) + "/" + fmt(s.max); };
  for (size_t k = 0; k < charts.size(); ++k) {
    const ChartFigures& f = charts[k];
    o << "tristim: chart " << k + 1 << " (" << f.name << "): " << f.patches << " patches";
    if (f.patches > 0) o << ", training mean/max dE00 " << pair(f.training_dE00);
    if (f.has_loo && f.patches > 0) o << ", leave-one-out mean/max dE00 " << pair(f.loo_dE00);
    o << ", held out (fitted on the other charts) mean/max dE00 "
      << (f.has_held_out ? pair(f.held_out_dE00) : "- (" + f.held_out_error + ")") << "\n";
  }
  return o.str();
}

std::string per_chart_compare(const Args& args, const PatchData& d, const FitOptions& options,
                              const std::vector<CompareRow>& rows, int white_index) {
  if (args.all("rgb").size() < 2) return "";
  for (const auto& r : rows) {
    if (!r.ok) continue;
    FitOptions o = options;
    o.objective = r.objective;
    std::string text = per_chart_figures(args, d.labels, evaluate_model(r.model_id, d.rgb, d.xyz, o, white_index));
    for (size_t at = 0; (at = text.find("tristim: ", at)) != std::string::npos;) text.replace(at, 9, "# ");
    return "\n# per chart, " + r.model_id + " (" + objective_id(r.objective) + "), the best row:\n" + text;
  }
  return "";
}

int patch_index(const std::vector<std::string>& ids, const std::string& id) {
  const std::string n = normalise_patch_id(id);
  for (size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == n) return static_cast<int>(i);
  for (size_t i = 0; i < ids.size(); ++i)  // several charts: an id without its chart's number is chart 1's
    if (ids[i] == "1:" + n) return static_cast<int>(i);
  throw Error(ErrorCode::UnknownId, "--white: no patch '" + id + "' in the RGB table");
}

std::string fit_methods_help() {
  const std::vector<MethodInfo> objectives = method_infos(objective_table());
  return models_help() + "\n" + methods_help("Objectives (--objective, --objectives)", objectives) + "\n" +
         linearisations_help();
}

FitOptions fit_options(const Args& args, const PatchData& d, int& white_index) {
  FitOptions o;
  o.objective = objective_from_id(args.get("objective", "ls"));
  o.white = parse_white(args, "lab-white", whites::D50());
  white_index = -1;
  if (args.has("white")) {
    white_index = patch_index(d.ids, args.get("white"));
    o.preserve_white = true;
    o.white_RGB = d.rgb.row(white_index).transpose();
    o.white_XYZ = d.xyz.row(white_index).transpose();
  }
  if (args.has("psm-max-iterations")) o.psm.max_iterations = static_cast<int>(args.get_double("psm-max-iterations", 0));
  if (args.has("psm-threshold")) o.psm.step_threshold = args.get_double("psm-threshold", 1e-6);
  if (args.has("de-algorithm")) o.de2000.algorithm = args.get("de-algorithm");
  o.de2000.rms = args.has("de-rms");
  o.de2000.initial_step = args.get_double("de-step", o.de2000.initial_step);
  o.de2000.xtol_rel = args.get_double("de-xtol", o.de2000.xtol_rel);
  o.de2000.ftol_rel = args.get_double("de-ftol", o.de2000.ftol_rel);
  o.de2000.max_evaluations = static_cast<int>(args.get_double("de-max-evaluations", o.de2000.max_evaluations));
  return o;
}

void write_bytes(const std::string& path, const void* data, size_t n) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw Error(ErrorCode::InvalidArgument, "cannot write '" + path + "'");
  f.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
  if (!f) throw Error(ErrorCode::ExportFailed, "writing '" + path + "' failed");
}

std::string ext_of(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : lower(path.substr(dot + 1));
}

std::string fmt(double v, int prec) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

}  // namespace tristim::cli

// tristim lab shen | table4 | guarnera: the colorimetry lab's exercises 3-5 (the papers' tables),
// each printed as the CSV the page downloads (lab_table_csv) or, with --json, the same table.
#include <ostream>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/error.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::cli {

/// The camera of a lab exercise: --sensitivities ssf.csv, or --camera <one of the 52>|cmf.
SpectralData lab_camera_arg(const Args& args, const std::string& fallback) {
  if (args.has("sensitivities")) return read_ssf_csv(read_file(args.get("sensitivities")), args.get("sensitivities"));
  const std::string camera = args.get("camera", fallback);
  return camera == "cmf" ? cmf_sensitivities() : camera_ssf(camera);
}

namespace {

void print_table(const Args& args, const LabTable& t, std::ostream& out) {
  if (!args.has("json")) {
    out << lab_table_csv(t);
    return;
  }
  out << fields::write(t).dump(1) << "\n";  // LabTable's field list (lab/exercises.hpp), as the page gets it
}

std::vector<int> integers(const std::string& text, const std::string& option) {
  std::vector<int> v;
  for (double d : numbers(text, option)) {
    if (d != static_cast<double>(static_cast<int>(d))) throw Error(ErrorCode::InvalidArgument, "--" + option + " expects integers");
    v.push_back(static_cast<int>(d));
  }
  return v;
}

std::uint64_t seed_arg(const Args& args) {
  const double s = args.get_double("seed", 1);
  if (!(s >= 0 && s < 1e15) || s != static_cast<double>(static_cast<std::uint64_t>(s)))
    throw Error(ErrorCode::InvalidArgument, "--seed expects a non-negative integer");
  return static_cast<std::uint64_t>(s);
}

std::string table_arg(const Args& args, const std::string& fallback, const std::vector<std::string>& allowed) {
  const std::string t = args.get("table", fallback);
  for (const auto& a : allowed)
    if (a == t) return t;
  throw Error(ErrorCode::InvalidArgument, "--table is " + allowed[0] + " or " + allowed[1] + ", not '" + t + "'");
}

int run_shen(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "sensitivities", "chart", "J", "sigma", "table-J", "table-sigma", "seeds", "seed", "table", "json"});
  const std::string which = table_arg(args, "L", {"L", "J"});
  ShenOptions o;
  o.chart = args.get("chart", o.chart);
  if (args.has("J")) o.J = integers(args.get("J"), "J");
  if (args.has("sigma")) o.sigmas = numbers(args.get("sigma"), "sigma");
  o.J_table = static_cast<int>(args.get_double("table-J", o.J_table));
  o.sigma_table = args.get_double("table-sigma", o.sigma_table);
  o.seeds = static_cast<int>(args.get_double("seeds", o.seeds));
  o.seed = seed_arg(args);
  if (which == "L") o.sigmas.clear();  // only the table's rows
  const ShenExercise e = lab_shen_exercise(lab_camera_arg(args, "Canon_EOS_5D_Mark_II"), o);
  print_table(args, which == "L" ? shen_l_table(e) : shen_j_table(e), out);
  return 0;
}

int run_table4(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "illuminant", "noise", "seed", "json"});
  print_table(args, table4_table(lab_table4_exercise(args.get("camera", "Nikon_D850"), args.get("illuminant", "D50"),
                                                     args.get_double("noise", kTable4Noise), seed_arg(args))), out);
  return 0;
}

int run_guarnera(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "sensitivities", "illuminant", "light", "training", "table", "json"});
  if (table_arg(args, "exposure", {"exposure", "table4"}) == "exposure") {
    print_table(args, exposure_table(lab_exposure_exercise(lab_camera_arg(args, "Canon_EOS_5D_Mark_II"),
                                                           illuminant_arg(args.get("illuminant", "D65")))), out);
    return 0;
  }
  if (args.has("sensitivities")) throw Error(ErrorCode::InvalidArgument, "--table table4 renders a built-in --camera");
  std::vector<std::string> lights{"D65", "A", "F2"}, trainings{"projector", "reflective"};
  if (args.has("light")) lights = args.all("light");
  if (args.has("training")) trainings = args.all("training");
  print_table(args, guarnera_table(lab_guarnera_table4(args.get("camera", "Canon_EOS_5D_Mark_II"), lights, trainings)), out);
  return 0;
}

}  // namespace

/// Exercises 3-5 (cmd_lab.cpp dispatches here); -1 when `sub` is not one of them.
int run_lab_exercise(const std::string& sub, const Args& args, std::ostream& out) {
  if (sub == "shen") return run_shen(args, out);
  if (sub == "table4") return run_table4(args, out);
  if (sub == "guarnera") return run_guarnera(args, out);
  return -1;
}

}  // namespace tristim::cli

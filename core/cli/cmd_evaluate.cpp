// CLI: `tristim evaluate` — a profile on test patches (JSON metrics).
#include <iostream>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim::cli {
namespace {
const char* kEvaluateUsage =
    "tristim evaluate --profile p.json --rgb test.csv --xyz ref.csv [--ref-white ...] [--csv out.csv]\n"
    "  Applies the profile to the test patches and prints JSON metrics (per patch and summaries), in\n"
    "  the order of test.csv. Every test patch must be in ref.csv; reference patches with no RGB (a\n"
    "  chart cut by the frame) are named on stderr and left out, as the page's held-out set does.";

int run_evaluate(const Args& args, std::ostream& out) {
  args.allow_only({"profile", "rgb", "xyz", "ref-white", "csv"});
  const Profile p = profile_from_json(read_file(args.get("profile")));
  const PatchData d = load_pairs(args.get("rgb"), args.get("xyz"), parse_white(args, "ref-white", whites::D50()), true);
  std::cerr << without_rgb_note("evaluate", "evaluated", d);
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

const CommandRegistration reg_eval({"evaluate", "evaluate a profile on test patches (JSON)", kEvaluateUsage, run_evaluate});

}  // namespace
}  // namespace tristim::cli

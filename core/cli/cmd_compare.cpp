// CLI: `tristim compare` — every model x objective on the same patches, sorted by held-out error.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "bootstrap_args.hpp"
#include "cli.hpp"
#include "linearise_option.hpp"
#include "patch_args.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/characterisation/ridge.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"

namespace tristim::cli {
namespace {
const char* kCompareUsage =
    "tristim compare --rgb patches.csv --xyz reference.csv [--rgb b.csv --xyz b_ref.csv ...] [--objectives ls,psm,de2000]\n"
    "                [--models id,id,...] [--white <patch>] [--lab-white ...] [--ref-white ...]\n"
    "                [--test-rgb other.csv --test-xyz other_ref.csv] [--json] [--threads N]\n"
    "                [--linearisation <id>[:options]|fitted.json [--reflectances spectra.csv|<chart>] [--full-scale 255]]\n"
    "                [--bootstrap N [--seed 1] [--level 0.95]] [--ridge]\n"
    "  Every model × objective on the same patches: training and leave-one-out CIEDE2000,\n"
    "  sorted by the held-out mean. With --test-rgb/--test-xyz also the train-on-one /\n"
    "  test-on-another table (Abed 2013 Table IV layout). The rows run on --threads threads\n"
    "  (default 0: one per hardware thread, at most 16); the numbers do not depend on it.\n"
    "  --bootstrap N: each row refitted on N resamples of the patches (and of each patch's pixels when\n"
    "  --rgb has sample's R_std,G_std,B_std,n): \"ci\": {\"level\",\"lo\",\"hi\"} next to the training and\n"
    "  leave-one-out mean dE00 (JSON), the leave-one-out interval as a column (text).\n"
    "  --ridge: each model also as ridge least squares, lambda chosen by closed-form leave-one-out\n"
    "  (\"ridge\" rows in JSON, a second table in text): many-term rows whose held-out figure depends on\n"
    "  the fit become stable.\n"
    "  Rows whose leave-one-out mean moves when the optimiser stops later (iterative objectives, condition\n"
    "  number > 1e4, stopping tolerances 100x tighter: by more than 0.05 or 2 %) are flagged LOO-unstable\n"
    "  (JSON: \"loo_stopping\": {\"flagged\", \"perturbed_loo_mean\"}).";

/// A row's bootstrap (evaluation/bootstrap.hpp): the row's model and objective refitted on resamples.
struct RowBootstrap {
  bool ok = false;
  BootstrapResult result;
  std::string error;
};

/// A row as its field list writes it (evaluation.hpp), with what only the CLI adds: the bootstrap's
/// intervals next to the means and how it ran, the stopping check's flag.
json::Value compare_row_json(const CompareRow& r, const RowBootstrap* b, const StoppingCheck& stop) {
  json::Value o = fields::write(r);
  if (b && b->ok) {
    o.set("train_dE00", with_ci(*o.find("train_dE00"), b->result.train_dE00_mean));
    if (r.has_loo && b->result.has_loo) o.set("loo_dE00", with_ci(*o.find("loo_dE00"), b->result.loo_dE00_mean));
  }
  if (stop.checked) o.set("loo_stopping", fields::write_picked(stop, {"flagged", "perturbed_loo_mean"}));
  if (b)
    o.set("bootstrap", b->ok ? fields::object({{"ok", true},
                                               {"resamples", b->result.resamples},
                                               {"failed", b->result.failed},
                                               {"resampling", b->result.pixels ? "patches+pixels" : "patches"}})
                             : fields::object({{"ok", false}, {"message", b->error}}));
  return o;
}

int run_compare(const Args& args, std::ostream& out) {
  args.allow_only({"rgb", "xyz", "objectives", "models", "white", "lab-white", "ref-white", "test-rgb",
                   "test-xyz", "json", "objective", "psm-max-iterations", "psm-threshold", "de-algorithm", "de-xtol",
                   "de-ftol", "de-max-evaluations", "de-rms", "de-step", "linearisation", "reflectances", "full-scale",
                   "threads", "bootstrap", "seed", "level", "ridge"});
  if (args.has("threads")) {
    const double n = args.get_double("threads", 0);
    if (!(n >= 0 && n <= 256 && n == static_cast<int>(n)))
      throw Error(ErrorCode::InvalidArgument, "--threads must be a whole number from 0 (one per hardware thread) to 256, got '" +
                                                  args.get("threads") + "'");
    set_compare_threads(static_cast<int>(n));
  }
  const Vec3 ref_white = parse_white(args, "ref-white", whites::D50());
  PatchData d = load_pairs(args, ref_white, true);  // several --rgb/--xyz: one table of their union (patch_args.hpp)
  std::cerr << without_rgb_note("compare", "compared", d);  // a chart cut by the frame, as tristim fit takes it
  const Linearisation lin = linearisation_option(args, "compare", d.ids, d.rgb, d.xyz, ref_white);  // linearise_option.hpp
  int white_index = -1;
  const FitOptions o = fit_options(args, d, white_index);
  std::vector<Objective> objectives;
  for (const auto& s : split_list(args.get("objectives", "ls,psm,de2000"))) objectives.push_back(objective_from_id(s));
  std::vector<std::string> models;
  if (args.has("models"))
    for (const auto& s : split_list(args.get("models"))) models.push_back(model_info(s).id);
  const auto rows = compare_models(d.rgb, d.xyz, o, models, objectives, white_index);
  // Rows whose leave-one-out figure moves with the optimiser's stopping point are flagged
  // (leave_one_out_stopping_check): iterative objectives on ill-conditioned designs only.
  std::vector<StoppingCheck> stop(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const CompareRow& r = rows[i];
    if (!r.ok || !r.has_loo) continue;
    FitOptions ro = o;
    ro.objective = r.objective;
    try {
      stop[i] = leave_one_out_stopping_check(r.model_id, d.rgb, d.xyz, ro, white_index, r.loo_dE00.mean, r.condition_number);
    } catch (const Error& e) {
      std::cerr << "tristim compare: " << r.model_id << " " << objective_id(r.objective) << ": stopping check: " << e.what() << "\n";
    }
  }
  std::vector<RowBootstrap> boot;
  if (args.has("bootstrap")) {
    // Each row again (its per-patch leave-one-out errors), then its resamples: rows × resamples fits.
    BootstrapOptions b = bootstrap_options(args, "compare", args.get("rgb"), d.ids, lin.choice.method == "identity");
    for (const auto& r : rows) {
      RowBootstrap rb;
      if (r.ok) {
        std::cerr << "tristim compare: bootstrap " << r.model_id << " " << objective_id(r.objective) << "\n";
        try {
          FitOptions ro = o;
          ro.objective = r.objective;
          const ModelEvaluation ev = evaluate_model(r.model_id, d.rgb, d.xyz, ro, white_index);
          b.loo_dE00 = ev.has_loo ? ev.loo.patches.dE00 : std::vector<double>{};
          rb.result = bootstrap_fit(r.model_id, d.rgb, d.xyz, ro, b);
          rb.ok = true;
        } catch (const Error& e) {
          rb.error = std::string(e.code_name()) + ": " + e.what();
        }
      } else {
        rb.error = "the fit was refused";
      }
      boot.push_back(rb);
    }
  }
  // --ridge: every model of the table (as compare lists them) by ridge least squares (ridge.hpp).
  std::vector<RidgeRow> ridge;
  if (args.has("ridge")) {
    std::vector<std::string> ids;
    for (const auto& r : rows)
      if (std::find(ids.begin(), ids.end(), r.model_id) == ids.end()) ids.push_back(r.model_id);
    for (const auto& id : ids) ridge.push_back(ridge_row(id, d.rgb, d.xyz, o));
  }
  std::vector<TransferCell> transfer;
  if (args.has("test-rgb") || args.has("test-xyz")) {
    PatchData t = load_pairs(args.get("test-rgb"), args.get("test-xyz"), ref_white, true);
    std::cerr << without_rgb_note("compare", "held out", t);  // as tristim evaluate and the page's held-out set
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
    for (size_t i = 0; i < rows.size(); ++i) a.push(compare_row_json(rows[i], boot.empty() ? nullptr : &boot[i], stop[i]));
    j.set("rows", a);
    if (args.has("ridge")) j.set("ridge", fields::write(ridge));
    if (!transfer.empty()) j.set("transfer", fields::write(transfer));
    out << j.dump(2) << "\n";
    return 0;
  }
  out << "# " << d.rgb.rows() << " patches; CIEDE2000 relative to white " << fmt(o.white[0], 4) << ","
      << fmt(o.white[1], 4) << "," << fmt(o.white[2], 4) << "; sorted by leave-one-out mean\n";
  out << std::left << std::setw(18) << "model" << std::setw(8) << "obj" << std::right << std::setw(6) << "terms"
      << std::setw(10) << "train" << std::setw(10) << "train" << std::setw(10) << "LOO" << std::setw(10) << "LOO"
      << std::setw(10) << "LOO" << std::setw(11) << "cond" << "  status" << (boot.empty() ? "" : "  (LOO mean CI)") << "\n";
  out << std::left << std::setw(18) << "" << std::setw(8) << "" << std::right << std::setw(6) << "" << std::setw(10)
      << "mean" << std::setw(10) << "max" << std::setw(10) << "mean" << std::setw(10) << "p95" << std::setw(10) << "max"
      << std::setw(11) << "" << "\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const CompareRow& r = rows[i];
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
        << fit_status_name(r.status);
    if (stop[i].flagged)
      out << " LOO-unstable (" << fmt(stop[i].perturbed_loo_mean) << " with 100x tighter stopping)";
    if (!boot.empty()) {
      const RowBootstrap& b = boot[i];
      if (b.ok && b.result.has_loo)
        out << "  [" << fmt(b.result.loo_dE00_mean.lo) << ", " << fmt(b.result.loo_dE00_mean.hi) << "] ("
            << fmt(b.result.level * 100, 0) << " %)";
      else
        out << "  -";
    }
    out << "\n";
  }
  out << per_chart_compare(args, d, o, rows, white_index);  // several charts: their figures apart
  if (!ridge.empty()) {
    out << "\n# ridge least squares, lambda (relative to the largest squared singular value) by leave-one-out\n";
    out << std::left << std::setw(18) << "model" << std::right << std::setw(6) << "terms" << std::setw(10) << "train"
        << std::setw(10) << "LOO" << std::setw(10) << "LOO" << std::setw(11) << "lambda" << "\n";
    out << std::left << std::setw(18) << "" << std::right << std::setw(6) << "" << std::setw(10) << "mean" << std::setw(10)
        << "mean" << std::setw(10) << "max" << "\n";
    for (const auto& r : ridge) {
      out << std::left << std::setw(18) << r.row.model_id << std::right << std::setw(6) << r.row.n_terms;
      if (!r.row.ok) {
        out << "  refused: " << r.row.error_code << " (" << r.row.message << ")\n";
        continue;
      }
      std::ostringstream l;
      l << std::setprecision(2) << std::scientific << r.lambda;
      out << std::setw(10) << fmt(r.row.train_dE00.mean) << std::setw(10) << fmt(r.row.loo_dE00.mean) << std::setw(10)
          << fmt(r.row.loo_dE00.max) << std::setw(11) << l.str() << "\n";
    }
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

const CommandRegistration reg_cmp({"compare", "every model x objective, sorted by held-out error", kCompareUsage, run_compare,
                                   fit_methods_help});

}  // namespace
}  // namespace tristim::cli

// The objectives table: ids, labels, references and option schemas from the option structs.
#include "tristim/characterisation/objectives.hpp"

#include "tristim/error.hpp"
#include "../citations.hpp"
#include "../table_lookup.hpp"

namespace tristim {

namespace {


std::vector<ObjectiveMethod> build_table() {
  const PatternSearchOptions psm;
  const DeltaE2000Options de;
  std::vector<ObjectiveMethod> t;
  t.push_back({{"ls", "Least squares",
                std::string("pseudo-inverse: ") + citation::kAbed2013 + ", eq (26); " + citation::kShen2008 + ", eq (25)", {}},
               Objective::LeastSquares});
  t.push_back({{"psm", "Pattern search: median + mean + max of the L1 XYZ error",
                std::string(citation::kGuarnera2018) + ", eqs (11)-(12), Algorithm 2",
                {number_option("initial_step", "Initial step Δ₀", psm.initial_step, 1e-9, 1e6, "first mesh size, relative to each output channel's scale"),
                 number_option("expansion", "Expansion α", psm.expansion, 1, 100, "mesh growth after a successful poll (α > 1)"),
                 number_option("contraction", "Contraction β", psm.contraction, 1e-6, 1, "mesh shrink after a failed poll (β < 1)"),
                 number_option("step_threshold", "Step threshold", psm.step_threshold, 1e-15, 1, "stop when the mesh is smaller"),
                 number_option("max_iterations", "Max iterations (0: 100 × variables)", psm.max_iterations, 0, 1e8,
                        "iteration limit", "integer")}},
               Objective::PatternSearch});
  OptionSpec alg;
  alg.name = "algorithm";
  alg.type = "choice";
  alg.label = "Algorithm";
  alg.default_text = de.algorithm;
  alg.choices = {"auto", "lm", "irls", "bobyqa", "sbplx", "newuoa", "praxis", "cobyla", "neldermead"};
  alg.description = "auto: Levenberg-Marquardt for the RMS loss, reweighted Levenberg-Marquardt (irls) for the mean";
  t.push_back({{"de2000", "CIEDE2000, mean or RMS (reweighted / plain Levenberg-Marquardt)", "CIEDE2000 under the stated white (CIE 142-2001)",
                {alg,
                 number_option("rms", "Minimise the RMS instead of the mean", de.rms ? 1 : 0, 0, 1,
                        "the loss OpenCV's ccm minimises", "boolean"),
                 number_option("xtol_rel", "Relative x tolerance", de.xtol_rel, 0, 1, "stop when coefficients change less"),
                 number_option("ftol_rel", "Relative f tolerance", de.ftol_rel, 0, 1, "stop when the loss changes less"),
                 number_option("max_evaluations", "Max evaluations (0: 200 × variables)", de.max_evaluations, 0, 1e8,
                        "evaluation limit", "integer"),
                 number_option("initial_step", "Initial step", de.initial_step, 1e-9, 1e3, "first step, relative to each output channel's scale")}},
               Objective::DeltaE2000});
  return t;
}

}  // namespace

const std::vector<ObjectiveMethod>& objective_table() {
  return built_once<&build_table>();
}

const ObjectiveMethod& objective_method(const std::string& id) {
  const Objective o = objective_from_id(id);
  if (const ObjectiveMethod* m = find_row(objective_table(), o, [](const ObjectiveMethod& r) { return r.objective; }))
    return *m;
  throw Error(ErrorCode::Internal, "objective table misses '" + id + "'");
}

void apply_objective_choice(const MethodChoice& choice, FitOptions& options) {
  const ObjectiveMethod& m = objective_method(choice.method);
  const MethodChoice c = complete_choice(m.info, choice);
  options.objective = m.objective;
  if (m.objective == Objective::PatternSearch) {
    options.psm.initial_step = choice_number(c, "initial_step");
    options.psm.expansion = choice_number(c, "expansion");
    options.psm.contraction = choice_number(c, "contraction");
    options.psm.step_threshold = choice_number(c, "step_threshold");
    options.psm.max_iterations = static_cast<int>(choice_number(c, "max_iterations"));
  } else if (m.objective == Objective::DeltaE2000) {
    options.de2000.algorithm = choice_text(c, "algorithm");
    options.de2000.rms = choice_number(c, "rms") != 0;
    options.de2000.xtol_rel = choice_number(c, "xtol_rel");
    options.de2000.ftol_rel = choice_number(c, "ftol_rel");
    options.de2000.max_evaluations = static_cast<int>(choice_number(c, "max_evaluations"));
    options.de2000.initial_step = choice_number(c, "initial_step");
  }
}

MethodChoice objective_choice(const FitOptions& options) {
  MethodChoice c;
  c.method = objective_id(options.objective);
  if (options.objective == Objective::PatternSearch) {
    c.parameters = {{"initial_step", options.psm.initial_step},
                    {"expansion", options.psm.expansion},
                    {"contraction", options.psm.contraction},
                    {"step_threshold", options.psm.step_threshold},
                    {"max_iterations", options.psm.max_iterations}};
  } else if (options.objective == Objective::DeltaE2000) {
    c.settings = {{"algorithm", options.de2000.algorithm}};
    c.parameters = {{"rms", options.de2000.rms ? 1.0 : 0.0},
                    {"xtol_rel", options.de2000.xtol_rel},
                    {"ftol_rel", options.de2000.ftol_rel},
                    {"max_evaluations", options.de2000.max_evaluations},
                    {"initial_step", options.de2000.initial_step}};
  }
  return c;
}

std::string objective_choice_label(const MethodChoice& choice) {
  const ObjectiveMethod& m = objective_method(choice.method);
  if (m.objective != Objective::DeltaE2000) return m.info.label;
  const MethodChoice c = complete_choice(m.info, choice);
  const bool rms = choice_number(c, "rms") != 0;
  const std::string& alg = choice_text(c, "algorithm");
  // "auto" runs lm for the RMS loss and irls for the mean (fit_de2000.cpp).
  const bool lm = alg == "lm" || (alg == "auto" && rms), irls = alg == "irls" || (alg == "auto" && !rms);
  const std::string how = lm ? "Levenberg-Marquardt" : irls ? "reweighted Levenberg-Marquardt" : "NLopt " + alg;
  return std::string("CIEDE2000 ") + (rms ? "RMS" : "mean") + " (" + how + ")";
}

}  // namespace tristim

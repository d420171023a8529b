// NLopt BOBYQA with box bounds, for the Phase I and Phase II surface fits.
#include "minimise.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>

#include "tristim/error.hpp"

namespace tristim::surface_detail {

namespace {

struct Call {
  const std::function<double(const double*)>* f;
  int evaluations = 0;
};

double trampoline(unsigned, const double* x, double*, void* data) {
  Call* c = static_cast<Call*>(data);
  ++c->evaluations;
  const double v = (*c->f)(x);
  return std::isfinite(v) ? v : 1e300;
}

}  // namespace

Minimum minimise_bounded(const std::function<double(const double*)>& f, std::vector<double> x0,
                         const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                         const std::string& what) {
  const size_t n = x0.size();
  Minimum m;
  for (size_t j = 0; j < n; ++j) x0[j] = std::min(std::max(x0[j], lb[j]), ub[j]);
  Call call{&f};
  if (n == 0) {
    m.x = x0;
    m.f = trampoline(0, x0.data(), nullptr, &call);
    m.evaluations = call.evaluations;
    return m;
  }
  std::vector<double> step(n);
  for (size_t j = 0; j < n; ++j) {
    // BOBYQA needs ub - lb >= 2 * step; start with a tenth of the box.
    step[j] = 0.1 * (ub[j] - lb[j]);
  }
  nlopt_opt opt = nlopt_create(NLOPT_LN_BOBYQA, static_cast<unsigned>(n));
  nlopt_set_min_objective(opt, trampoline, &call);
  nlopt_set_lower_bounds(opt, lb.data());
  nlopt_set_upper_bounds(opt, ub.data());
  nlopt_set_initial_step(opt, step.data());
  nlopt_set_xtol_rel(opt, 1e-10);
  nlopt_set_ftol_rel(opt, 1e-14);
  nlopt_set_maxeval(opt, max_evaluations);
  double fmin = 0;
  const nlopt_result res = nlopt_optimize(opt, x0.data(), &fmin);
  nlopt_destroy(opt);
  if (res < 0 && res != NLOPT_ROUNDOFF_LIMITED)
    throw Error(ErrorCode::FitFailed, what + ": NLopt BOBYQA failed (code " + std::to_string(static_cast<int>(res)) + ")");
  m.x = x0;
  m.f = trampoline(0, x0.data(), nullptr, &call);  // the value at the returned point
  m.evaluations = call.evaluations;
  m.hit_limit = res == NLOPT_MAXEVAL_REACHED;
  return m;
}

Minimum minimise_from_starts(const std::function<double(const double*)>& f, const std::vector<std::vector<double>>& starts,
                             const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                             const std::string& what) {
  Minimum best;
  int evaluations = 0;
  bool have = false;
  for (const auto& s : starts) {
    Minimum m = minimise_bounded(f, s, lb, ub, max_evaluations, what);
    evaluations += m.evaluations;
    if (!have || m.f < best.f) best = m;
    have = true;
  }
  best.evaluations = evaluations;
  return best;
}

}  // namespace tristim::surface_detail

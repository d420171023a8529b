// NLopt BOBYQA with box bounds, for the Phase I and Phase II surface fits.
#include "minimise.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "../optimise/bounded.hpp"
#include "tristim/error.hpp"

namespace tristim::surface_detail {

namespace {

// One start: BOBYQA from x0 clamped into the box, then f once more at the point it returned
// (counted), which is the value reported.
Minimum minimise_from(const std::function<double(const double*)>& f, std::vector<double> x0,
                      const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                      const std::string& what) {
  const size_t n = x0.size();
  const auto finite_f = [&f](const double* x) {
    const double v = f(x);
    return std::isfinite(v) ? v : 1e300;
  };
  Minimum m;
  for (size_t j = 0; j < n; ++j) x0[j] = std::min(std::max(x0[j], lb[j]), ub[j]);
  if (n == 0) {
    m.x = x0;
    m.f = finite_f(x0.data());
    m.evaluations = 1;
    return m;
  }
  optimise::BoundedOptions bounded;  // BOBYQA
  bounded.lower = lb;
  bounded.upper = ub;
  bounded.initial_step.resize(n);
  for (size_t j = 0; j < n; ++j) {
    // BOBYQA needs ub - lb >= 2 * step; start with a tenth of the box.
    bounded.initial_step[j] = 0.1 * (ub[j] - lb[j]);
  }
  bounded.xtol_rel = 1e-10;
  bounded.ftol_rel = 1e-14;
  bounded.max_evaluations = max_evaluations;
  const optimise::BoundedMinimum r = optimise::minimise_bounded(finite_f, std::move(x0), bounded);
  if (r.failed) throw Error(ErrorCode::FitFailed, what + ": " + r.message);
  m.x = r.x;
  m.f = finite_f(m.x.data());  // the value at the returned point
  m.evaluations = r.evaluations + 1;
  m.hit_limit = r.hit_limit;
  return m;
}

}  // namespace

Minimum minimise_from_starts(const std::function<double(const double*)>& f, const std::vector<std::vector<double>>& starts,
                             const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                             const std::string& what) {
  Minimum best;
  int evaluations = 0;
  bool have = false;
  for (const auto& s : starts) {
    Minimum m = minimise_from(f, s, lb, ub, max_evaluations, what);
    evaluations += m.evaluations;
    if (!have || m.f < best.f) best = m;
    have = true;
  }
  best.evaluations = evaluations;
  return best;
}

}  // namespace tristim::surface_detail

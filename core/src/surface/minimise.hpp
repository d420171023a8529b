// Bounded derivative-free minimisation for the surface fits (NLopt BOBYQA), internal to core/src/surface.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace tristim::surface_detail {

struct Minimum {
  std::vector<double> x;
  double f = 0;
  int evaluations = 0;
  bool hit_limit = false;
};

/// Minimises f over lb <= x <= ub from x0 (clamped into the box) with NLopt's LN_BOBYQA
/// (a non-finite f counts as 1e300). Error(FitFailed) when NLopt reports a failure.
Minimum minimise_bounded(const std::function<double(const double*)>& f, std::vector<double> x0,
                         const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                         const std::string& what);

/// The best of several starts (each minimised; evaluations summed).
Minimum minimise_from_starts(const std::function<double(const double*)>& f, const std::vector<std::vector<double>>& starts,
                             const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                             const std::string& what);

}  // namespace tristim::surface_detail

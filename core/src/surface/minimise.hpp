// Bounded derivative-free minimisation for the surface fits (NLopt BOBYQA through
// optimise/bounded.hpp), internal to core/src/surface.
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

/// The best of several starts, each minimised over lb <= x <= ub from the start clamped into the
/// box with NLopt's LN_BOBYQA (a non-finite f counts as 1e300); evaluations summed.
/// Error(FitFailed) when NLopt reports a failure.
Minimum minimise_from_starts(const std::function<double(const double*)>& f, const std::vector<std::vector<double>>& starts,
                             const std::vector<double>& lb, const std::vector<double>& ub, int max_evaluations,
                             const std::string& what);

}  // namespace tristim::surface_detail

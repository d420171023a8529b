// Internal to core/src: the one door to NLopt's derivative-free optimisers under box bounds, for
// the CIEDE2000 fit (characterisation), Guarnera 2018's eq 8 OECF (linearisation) and the surface
// fits. Only bounded.cpp includes nlopt.h; NLopt is compiled from Debian's source in every build
// (cmake/nlopt.cmake), so a run takes the same steps natively and in wasm.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tristim::optimise {

/// NLopt's local derivative-free algorithms the core offers (NLOPT_LN_BOBYQA, NLOPT_LN_SBPLX,
/// NLOPT_LN_NEWUOA_BOUND, NLOPT_LN_PRAXIS, NLOPT_LN_COBYLA, NLOPT_LN_NELDERMEAD).
enum class Algorithm { Bobyqa, Sbplx, Newuoa, Praxis, Cobyla, NelderMead };
/// "bobyqa" | "sbplx" | "newuoa" | "praxis" | "cobyla" | "neldermead"; nullopt for another id.
std::optional<Algorithm> algorithm_from_id(const std::string& id);

/// One run's settings, applied in NLopt's calls in this order: bounds, initial step, xtol_rel,
/// ftol_rel, maxeval, then the seed just before the run. Zero tolerances and max_evaluations
/// <= 0 switch that test off (NLopt's convention).
struct BoundedOptions {
  Algorithm algorithm = Algorithm::Bobyqa;
  std::vector<double> lower, upper;   ///< the box, one bound per variable
  std::vector<double> initial_step;   ///< per variable; empty: NLopt's own first step
  double xtol_rel = 0;
  double ftol_rel = 0;
  int max_evaluations = 0;
  /// nlopt_srand(seed) before the run: NLopt's random numbers (PRAXIS uses them) are otherwise
  /// seeded from the clock. NLopt's generator state is per thread natively, global in wasm.
  std::optional<unsigned long> seed;
};

/// What a run ended with (like Ceres's Solver::Summary).
struct BoundedMinimum {
  std::vector<double> x;  ///< the point NLopt returned (the start when it failed at once)
  double f = 0;           ///< NLopt's value for it
  int evaluations = 0;    ///< objective calls during the run
  int code = 0;           ///< the nlopt_result
  bool hit_limit = false; ///< stopped at max_evaluations (NLOPT_MAXEVAL_REACHED)
  bool failed = false;    ///< code < 0 other than NLOPT_ROUNDOFF_LIMITED (which keeps a usable x)
  std::string message;    ///< empty, or e.g. "NLopt BOBYQA failed (code -1)"
};

/// Minimises f (called with x[0 .. x0.size())) over the box from x0, which must lie in it. A
/// failure is reported, not thrown (callers differ in what they keep); an exception from f stops
/// the run and is rethrown. Error(FitFailed) if NLopt cannot create the optimiser,
/// Error(InvalidArgument) if a bound or step vector has another size than x0.
BoundedMinimum minimise_bounded(const std::function<double(const double* x)>& f, std::vector<double> x0,
                                const BoundedOptions& options);

}  // namespace tristim::optimise

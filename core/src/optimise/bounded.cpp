// NLopt's bounded derivative-free optimisers behind one call (optimise/bounded.hpp).
#include "bounded.hpp"

#include <nlopt.h>

#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <utility>

#include "tristim/error.hpp"

namespace tristim::optimise {

namespace {

struct Algo {
  const char* id;
  const char* name;  // in messages
  Algorithm algorithm;
  nlopt_algorithm nlopt;
};

const Algo kAlgorithms[] = {
    {"bobyqa", "BOBYQA", Algorithm::Bobyqa, NLOPT_LN_BOBYQA},
    {"sbplx", "SBPLX", Algorithm::Sbplx, NLOPT_LN_SBPLX},
    {"newuoa", "NEWUOA", Algorithm::Newuoa, NLOPT_LN_NEWUOA_BOUND},
    {"praxis", "PRAXIS", Algorithm::Praxis, NLOPT_LN_PRAXIS},
    {"cobyla", "COBYLA", Algorithm::Cobyla, NLOPT_LN_COBYLA},
    {"neldermead", "Nelder-Mead", Algorithm::NelderMead, NLOPT_LN_NELDERMEAD},
};

const Algo& algo(Algorithm a) {
  for (const Algo& x : kAlgorithms)
    if (x.algorithm == a) return x;
  throw Error(ErrorCode::InvalidArgument, "unknown optimiser");
}

struct Call {
  const std::function<double(const double*)>* f = nullptr;
  nlopt_opt opt = nullptr;
  int evaluations = 0;
  std::exception_ptr error;  // thrown by f: NLopt is C, so it must not unwind through it
};

double trampoline(unsigned, const double* x, double*, void* data) {
  Call* c = static_cast<Call*>(data);
  ++c->evaluations;
  try {
    return (*c->f)(x);
  } catch (...) {
    c->error = std::current_exception();
    nlopt_force_stop(c->opt);
    return HUGE_VAL;
  }
}

}  // namespace

std::optional<Algorithm> algorithm_from_id(const std::string& id) {
  for (const Algo& x : kAlgorithms)
    if (id == x.id) return x.algorithm;
  return std::nullopt;
}

BoundedMinimum minimise_bounded(const std::function<double(const double* x)>& f, std::vector<double> x0,
                                const BoundedOptions& options) {
  const std::size_t n = x0.size();
  if (options.lower.size() != n || options.upper.size() != n ||
      (!options.initial_step.empty() && options.initial_step.size() != n))
    throw Error(ErrorCode::InvalidArgument, "bounded minimisation: bounds or steps do not match the variables");
  const Algo& a = algo(options.algorithm);
  std::unique_ptr<nlopt_opt_s, void (*)(nlopt_opt)> opt(nlopt_create(a.nlopt, static_cast<unsigned>(n)), nlopt_destroy);
  if (!opt) throw Error(ErrorCode::FitFailed, "NLopt could not create the optimiser");
  Call call;
  call.f = &f;
  call.opt = opt.get();
  nlopt_set_min_objective(opt.get(), trampoline, &call);
  nlopt_set_lower_bounds(opt.get(), options.lower.data());
  nlopt_set_upper_bounds(opt.get(), options.upper.data());
  if (!options.initial_step.empty()) nlopt_set_initial_step(opt.get(), options.initial_step.data());
  nlopt_set_xtol_rel(opt.get(), options.xtol_rel);
  nlopt_set_ftol_rel(opt.get(), options.ftol_rel);
  nlopt_set_maxeval(opt.get(), options.max_evaluations);
  if (options.seed) nlopt_srand(*options.seed);
  BoundedMinimum m;
  const nlopt_result res = nlopt_optimize(opt.get(), x0.data(), &m.f);
  opt.reset();
  if (call.error) std::rethrow_exception(call.error);
  m.x = std::move(x0);
  m.evaluations = call.evaluations;
  m.code = static_cast<int>(res);
  m.hit_limit = res == NLOPT_MAXEVAL_REACHED;
  m.failed = res < 0 && res != NLOPT_ROUNDOFF_LIMITED;
  if (m.failed)
    m.message = std::string("NLopt ") + a.name + " failed (code " + std::to_string(m.code) + ")";
  else if (m.hit_limit)
    m.message =
        std::string("NLopt ") + a.name + " reached its evaluation limit (" + std::to_string(m.evaluations) + ")";
  return m;
}

}  // namespace tristim::optimise

// Guarnera 2018 Algorithm 2: the generalised pattern search on eq (11), median + mean + max of the
// per-patch L1 errors of eq (12), started from least squares.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "fit_problem.hpp"
#include "tristim/error.hpp"

namespace tristim::fit_detail {

namespace {

// The median of E (for even N the mean of its two middle values), found among the E_i in
// [lo, hi] only: when the order statistics the median needs (h = N/2, and h − 1 for even N) lie
// in that window, selecting among the few values there replaces the O(N) selection over all of E
// and gives the same doubles. Otherwise (the window was too narrow) all of E is used.
// `lower`, `upper`: E's order statistics h − 1 (h for odd N) and h, to centre the next window.
double windowed_median(const Eigen::VectorXd& E, double lo, double hi, std::vector<double>& scratch,
                       double& lower, double& upper) {
  const Eigen::Index n = E.size(), h = n / 2;
  const Eigen::Index need = n % 2 == 0 ? h - 1 : h;  // the lowest rank needed
  scratch.resize(static_cast<std::size_t>(n));         // no-op after the first call
  double* w = scratch.data();
  Eigen::Index below = 0, inside = 0;
  for (Eigen::Index i = 0; i < n; ++i) {  // branch-free: every x is written, kept when inside
    const double x = E[i];
    below += x < lo;
    w[inside] = x;
    inside += (x >= lo) & (x <= hi);
  }
  if (!(below <= need && below + inside > h)) {
    std::copy(E.data(), E.data() + n, w);
    below = 0;
    inside = n;
  }
  double* mid = w + (h - below);
  std::nth_element(w, mid, w + inside);
  upper = *mid;
  lower = n % 2 == 0 ? *std::max_element(w, mid) : upper;
  return n % 2 == 0 ? 0.5 * (upper + lower) : upper;
}

}  // namespace

// Guarnera 2018 Algorithm 2 on z (Q × 3), coordinate directions ±e, opportunistic poll.
Outcome pattern_search(const Problem& pr, const PatternSearchOptions& o, Eigen::MatrixXd& z) {
  Outcome out;
  const int nvar = pr.q * 3;
  const int max_iter = o.max_iterations > 0 ? o.max_iterations : 100 * nvar;
  if (!(o.expansion > 1) || !(o.contraction > 0 && o.contraction < 1) || !(o.initial_step > 0) ||
      !(o.step_threshold > 0))
    throw Error(ErrorCode::InvalidArgument,
                "pattern search needs expansion > 1, 0 < contraction < 1, initial step > 0 and threshold > 0");
  Eigen::MatrixXd Rz = pr.predictions(z) - pr.Y;  // N × 3 residuals
  Eigen::Vector3d scale;
  for (int c = 0; c < 3; ++c) {
    scale[c] = pr.Y.col(c).norm();
    if (!(scale[c] > 0)) scale[c] = 1;
  }
  Eigen::VectorXd E = Rz.cwiseAbs().rowwise().sum();
  std::vector<double> scratch;
  double lower = 0, upper = 0;
  // eq (11): median(E) + mean(E) + max(E), with E the per-patch L1 error of eq (12).
  double f = windowed_median(E, -INFINITY, INFINITY, scratch, lower, upper) + E.mean() + E.maxCoeff();
  out.f0 = f;
  // A trial moves one coefficient z(j, c) by `step`, so each E_i moves by at most |step|·|B_ij|,
  // and so does each order statistic of E. The median's order statistics of the trial are thus
  // within |step|·max_i |B_ij| of the current ones: windowed_median selects among the few E_i
  // there (the exact median, the same as over all of E; its O(N) selection was ~70 % of the
  // search's time).
  const Eigen::VectorXd Bmax = pr.B.cwiseAbs().colwise().maxCoeff().transpose();
  Eigen::VectorXd trialE(pr.n), trialCol(pr.n);
  double delta = o.initial_step;
  int k = 0;
  for (; delta > o.step_threshold && k < max_iter; ++k) {
    bool improved = false;
    for (int v = 0; v < nvar && !improved; ++v) {
      const int c = v / pr.q, j = v % pr.q;
      for (int sgn = 1; sgn >= -1 && !improved; sgn -= 2) {
        const double step = sgn * delta * scale[c];
        trialCol = Rz.col(c) + step * pr.B.col(j);
        trialE = E - Rz.col(c).cwiseAbs() + trialCol.cwiseAbs();
        ++out.evaluations;
        const double reach = std::fabs(step) * Bmax[j] * (1 + 1e-9) + 1e-12 * (std::fabs(upper) + 1e-300);
        double trial_lower = 0, trial_upper = 0;
        const double ft = windowed_median(trialE, lower - reach, upper + reach, scratch, trial_lower, trial_upper) +
                          trialE.mean() + trialE.maxCoeff();
        if (ft < f) {
          f = ft;
          lower = trial_lower;
          upper = trial_upper;
          E = trialE;
          Rz.col(c) = trialCol;
          z(j, c) += step;
          improved = true;
        }
      }
    }
    delta *= improved ? o.expansion : o.contraction;
  }
  out.iterations = k;
  out.hit_limit = delta > o.step_threshold;
  out.f = f;
  return out;
}

}  // namespace tristim::fit_detail

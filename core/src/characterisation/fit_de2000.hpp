// Internal to core/src/characterisation: the CIEDE2000 loss and its residuals (fit_de2000.cpp), and
// the Gauss–Newton minimisers over them (fit_de2000_gauss_newton.cpp). Not installed.
#pragma once
#include <vector>

#include "fit_problem.hpp"

namespace tristim::fit_detail {

/// The loss's data: reference Lab under `white`, per-patch weights w (Σ = wsum), mean or RMS.
struct De2000Data {
  const Problem* pr;
  Eigen::MatrixXd Lab_ref;  // N × 3
  std::vector<double> w;
  double wsum;
  Vec3 white;
  bool rms = false;
};

/// The loss at x (z stored channel-major): Σ w_i ΔE00_i / Σ w, or its RMS; a non-finite ΔE00 counts as 1e6.
double de2000_cost(const Problem& pr, const De2000Data& d, const double* x);
/// The weighted three squares of every patch at x, and their Jacobian blocks G (fit_de2000.cpp).
void de2000_residuals(const Problem& pr, const De2000Data& d, const double* x, Eigen::VectorXd& r,
                      std::vector<Mat3>* G, std::vector<Vec3>& qs, bool qs_at_x);

/// RMS loss: Levenberg–Marquardt from x (fit_de2000_gauss_newton.cpp).
void levenberg_marquardt(const Problem& pr, const De2000Data& d, const FitOptions& options, std::vector<double>& x,
                         Outcome& out);
/// Mean loss: reweighted, damped Gauss–Newton from x (fit_de2000_gauss_newton.cpp).
void reweighted_lm(const Problem& pr, const De2000Data& d, const FitOptions& options, std::vector<double>& x,
                   Outcome& out);

}  // namespace tristim::fit_detail

// Internal to core/src/characterisation: the problem every objective of fit.hpp works on (the
// equilibrated design, with white-point preservation as a null-space parametrisation) and the
// objective families' entry points, one file each; fit.cpp dispatches to them. Not installed.
#pragma once
#include <Eigen/Core>

#include "tristim/characterisation/fit.hpp"

namespace tristim::fit_detail {

// The fit problem in equilibrated coordinates: A_s = A·diag(s); coefficients in those
// coordinates X_s (P × 3) = Xp + Z·z, z (Q × 3) free. Unconstrained: Xp = 0, Z = I.
struct Problem {
  const ModelInfo* info = nullptr;
  Eigen::Index n = 0;
  int p = 0, q = 0;
  Eigen::VectorXd s;     // column scales
  Eigen::MatrixXd As;    // N × P
  Eigen::MatrixXd Z;     // P × Q
  Eigen::MatrixXd Xp;    // P × 3
  Eigen::MatrixXd B;     // N × Q  = As·Z
  Eigen::MatrixXd base;  // N × 3  = As·Xp
  Eigen::MatrixXd Y;     // N × 3
  bool constrained = false;

  Eigen::MatrixXd coefficients(const Eigen::MatrixXd& z) const {  // 3 × P, absolute units
    // Unconstrained, Z = I: Z·z is z itself (every other product is a zero), so it is skipped;
    // Xp + z still turns a −0 into +0 as the product did.
    Eigen::MatrixXd Xs = constrained ? Eigen::MatrixXd(Xp + Z * z) : Eigen::MatrixXd(Xp + z);
    return (s.asDiagonal() * Xs).transpose();
  }
  Eigen::MatrixXd predictions(const Eigen::MatrixXd& z) const { return base + B * z; }
};

/// Validates the patches and options, builds the equilibrated design and, with
/// options.preserve_white, the constraint's null space (fit.cpp).
Problem make_problem(const ModelInfo& info, const PatchMatrix& rgb, const PatchMatrix& xyz,
                     const FitOptions& options);
/// The first camera channel (0..2) that is constant over rgb's rows (row `skip` left out), or -1.
int constant_channel(const PatchMatrix& rgb, Eigen::Index skip = -1);

/// How an iterative objective went (pattern search, CIEDE2000).
struct Outcome {
  int iterations = 0, evaluations = 0;
  double f0 = 0, f = 0;
  bool hit_limit = false;
};

/// Least squares in the free coordinates (fit_least_squares.cpp).
Eigen::MatrixXd solve_ls(const Problem& pr, const FitOptions& options, double& cond);
/// Guarnera 2018 Algorithm 2 from z (fit_pattern_search.cpp).
Outcome pattern_search(const Problem& pr, const PatternSearchOptions& o, Eigen::MatrixXd& z);
/// Mean or RMS CIEDE2000 from z (fit_de2000.cpp).
Outcome minimise_de2000(const Problem& pr, const FitOptions& options, Eigen::MatrixXd& z);

/// The dispatcher behind fit() (fit.cpp); leave_one_out.cpp refits the white patch's fold with it.
FitResult fit_info(const ModelInfo& info, const PatchMatrix& rgb, const PatchMatrix& xyz,
                   const FitOptions& options);

}  // namespace tristim::fit_detail

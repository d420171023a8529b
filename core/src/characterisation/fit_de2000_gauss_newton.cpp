// The CIEDE2000 objective's Gauss–Newton minimisers: Levenberg–Marquardt for the RMS loss, a
// reweighted, damped Gauss–Newton for the mean; both on the residuals of de2000_residuals.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "fit_de2000.hpp"

namespace tristim::fit_detail {

namespace {

// The normal equations A = Σ_i J_iᵀ W_i J_i and g = Σ_i J_iᵀ v_i for Jacobian rows with the structure
// of de2000_residuals, J_i(m, c·Q + j) = G_i(m, c)·B(i, j), from M_i = G_iᵀ W_i G_i (3 × 3, symmetric)
// and u_i = G_iᵀ v_i (3): A(c·Q + j, c'·Q + j') = Σ_i M_i(c, c')·B(i, j)·B(i, j') and
// g(c·Q + j) = Σ_i u_i(c)·B(i, j). The same sums as the dense products Jᵀ(WJ) and Jᵀv, in
// 6·N·Q² multiply-adds instead of 2·3N·(3Q)² (natively, the dense J and its GEMM were 40 % of the
// mean-ΔE00 fits' time; in wasm Eigen's GEMM is scalar code).
// M: N × 6 (columns (0,0), (0,1), (0,2), (1,1), (1,2), (2,2)), u: N × 3. acc: scratch.
void normal_equations(const Problem& pr, const Eigen::Matrix<double, Eigen::Dynamic, 6>& M,
                      const Eigen::Matrix<double, Eigen::Dynamic, 3>& u, std::vector<double>& acc,
                      Eigen::MatrixXd& A, Eigen::VectorXd& g) {
  const int q = pr.q;
  const std::size_t qq = static_cast<std::size_t>(q) * static_cast<std::size_t>(q);
  acc.assign(6 * qq, 0.0);
  for (Eigen::Index i = 0; i < pr.n; ++i) {
    double m[6];
    for (int p = 0; p < 6; ++p) m[p] = M(i, p);
    for (int j = 0; j < q; ++j) {
      const double bij = pr.B(i, j);
      double* row = acc.data() + 6 * static_cast<std::size_t>(j) * static_cast<std::size_t>(q);
      for (int k = 0; k <= j; ++k) {  // lower triangle of each block: B(i,j)·B(i,k) is symmetric in j, k
        const double bb = bij * pr.B(i, k);
        for (int p = 0; p < 6; ++p) row[6 * k + p] += m[p] * bb;
      }
    }
  }
  static const int pc[6] = {0, 0, 0, 1, 1, 2}, pd[6] = {0, 1, 2, 1, 2, 2};
  for (int p = 0; p < 6; ++p) {
    const int c = pc[p], e = pd[p];
    for (int j = 0; j < q; ++j)
      for (int k = 0; k <= j; ++k) {
        const double v = acc[6 * (static_cast<std::size_t>(j) * static_cast<std::size_t>(q) + static_cast<std::size_t>(k)) + static_cast<std::size_t>(p)];
        A(c * q + j, e * q + k) = v;
        A(e * q + k, c * q + j) = v;
        A(c * q + k, e * q + j) = v;
        A(e * q + j, c * q + k) = v;
      }
  }
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < q; ++j) {
      double s = 0;
      for (Eigen::Index i = 0; i < pr.n; ++i) s += u(i, c) * pr.B(i, j);
      g[c * q + j] = s;
    }
}

// The damped Gauss–Newton iteration both CIEDE2000 paths share: steps (A + μI) h = −g from the
// linearisation at x, accepted on the gain ratio ρ = (F − F_new) / predicted. Damping update and
// stopping tests: Madsen, Nielsen & Tingleff (2004), "Methods for non-linear least squares
// problems", Algorithm 3.16 (μ0 = τ·max diag A, τ = 1e-3; μ ← μ·max(1/3, 1-(2ρ-1)³) or μ·ν, ν ← 2ν),
// with tests ‖g‖∞ ≤ 1e-12·(1 + F), ‖h‖ ≤ xtol_rel·(‖x‖ + xtol_rel) and small_decrease(F, F_new).
// linearise() refreshes A and g at x and returns the loss there; trial(x_new) the loss at x_new;
// (after a step is accepted, F keeps trial's value);
// predicted(h, μ) the model's decrease for step h.
template <class Linearise, class Trial, class Predicted, class SmallDecrease>
void damped_gauss_newton(Eigen::Map<Eigen::VectorXd>& xv, const Eigen::MatrixXd& A, const Eigen::VectorXd& g, int max_iter,
                         double xtol, Outcome& out, Linearise linearise, Trial trial, Predicted predicted,
                         SmallDecrease small_decrease) {
  const Eigen::Index nvar = xv.size();
  Eigen::VectorXd h(nvar), x_new(nvar);
  Eigen::MatrixXd Am(nvar, nvar);
  Eigen::LLT<Eigen::MatrixXd> llt(nvar);
  double F = linearise();
  double mu = 1e-3 * A.diagonal().maxCoeff(), nu = 2.0;
  int k = 0;
  bool converged = !(mu > 0) || g.lpNorm<Eigen::Infinity>() <= 1e-12 * (1.0 + F);
  while (!converged && k < max_iter) {
    ++k;
    Am = A;
    Am.diagonal().array() += mu;
    // A + μI is positive definite (A is a sum of J_iᵀ·(positive semi-definite)·J_i, μ > 0): Cholesky,
    // which needs no pivot search; LDLT only if rounding made it fail.
    llt.compute(Am);
    if (llt.info() == Eigen::Success) h = llt.solve(-g);
    else h = Am.ldlt().solve(-g);
    if (!h.allFinite()) break;
    if (h.norm() <= xtol * (xv.norm() + xtol)) {
      converged = true;
      break;
    }
    x_new = xv + h;
    const double F_new = trial(x_new);
    const double pred = predicted(h, mu);
    const double rho = pred > 0 ? (F - F_new) / pred : -1.0;
    if (rho > 0 && F_new < F) {
      const bool small = small_decrease(F, F_new);
      xv = x_new;
      F = F_new;
      linearise();
      const double t = 2.0 * rho - 1.0;
      mu *= std::max(1.0 / 3.0, 1.0 - t * t * t);
      nu = 2.0;
      converged = small || g.lpNorm<Eigen::Infinity>() <= 1e-12 * (1.0 + F);
    } else {
      mu *= nu;
      nu *= 2.0;
    }
  }
  out.iterations = k;
  out.hit_limit = !converged && k >= max_iter;
}

// What both CIEDE2000 iterations below keep between steps: the residuals at x (r) and at the trial
// point (r_new), the normal equations (A, g) and their per-patch blocks (G, M, u, acc), and the last
// trial point, whose squares (qs) de2000_residuals reuses once the step to it is accepted.
struct GaussNewtonScratch {
  Eigen::VectorXd r, r_new, g;
  Eigen::MatrixXd A;
  std::vector<Mat3> G;
  Eigen::Matrix<double, Eigen::Dynamic, 6> M;
  Eigen::Matrix<double, Eigen::Dynamic, 3> u;
  std::vector<double> acc;
  std::vector<Vec3> qs;  // the squares at the last trial point, x_trial
  Eigen::VectorXd x_trial;
  bool trialled = false;

  GaussNewtonScratch(Eigen::Index n, int nvar)
      : r(3 * n), r_new(3 * n), g(nvar), A(nvar, nvar), G(static_cast<std::size_t>(n)), M(n, 6), u(n, 3) {}
  /// r and the Jacobian blocks G at x.
  void linearise_at(const Problem& pr, const De2000Data& d, const Eigen::Map<Eigen::VectorXd>& x) {
    de2000_residuals(pr, d, x.data(), r, &G, qs, trialled && x_trial == x);
  }
  /// r_new at a trial point.
  void trial_at(const Problem& pr, const De2000Data& d, const Eigen::VectorXd& x_new) {
    de2000_residuals(pr, d, x_new.data(), r_new, nullptr, qs, false);
    x_trial = x_new;
    trialled = true;
  }
};

}  // namespace

// The RMS loss is a sum of squares, sqrt(Σ w_i ΔE_i² / Σ w_i): minimised by Levenberg–Marquardt on
// the 3N residuals of de2000_residuals (damped_gauss_newton with A = JᵀJ, g = Jᵀr, F = ‖r‖², the
// predicted decrease hᵀ(μh − g) = 2·(L(0) − L(h)), and a relative decrease of the RMS below
// ftol_rel), started from least squares, unbounded (the box of the derivative-free path is only its
// trust region). evaluations counts residual vectors (a linearisation counts 4: the residuals and
// one difference per Lab axis, as before the residuals at an accepted trial point were reused and
// the L* difference made cheap, so the limit max_evaluations / 4 iterations keeps its meaning).
void levenberg_marquardt(const Problem& pr, const De2000Data& d, const FitOptions& options, std::vector<double>& x,
                         Outcome& out) {
  const int nvar = static_cast<int>(x.size());
  const int max_iter = options.de2000.max_evaluations > 0 ? std::max(1, options.de2000.max_evaluations / 4) : 100;
  const double ftol = options.de2000.ftol_rel;
  GaussNewtonScratch gn(pr.n, nvar);
  Eigen::Map<Eigen::VectorXd> xv(x.data(), nvar);
  damped_gauss_newton(
      xv, gn.A, gn.g, max_iter, options.de2000.xtol_rel, out,
      [&] {
        gn.linearise_at(pr, d, xv);
        out.evaluations += 4;
        for (Eigen::Index i = 0; i < pr.n; ++i) {  // A = JᵀJ, g = Jᵀr
          const Mat3& Gi = gn.G[static_cast<std::size_t>(i)];
          const Mat3 Mi = Gi.transpose() * Gi;
          gn.M.row(i) << Mi(0, 0), Mi(0, 1), Mi(0, 2), Mi(1, 1), Mi(1, 2), Mi(2, 2);
          gn.u.row(i) = (Gi.transpose() * Vec3(gn.r.segment<3>(3 * i))).transpose();
        }
        normal_equations(pr, gn.M, gn.u, gn.acc, gn.A, gn.g);
        return gn.r.squaredNorm();
      },
      [&](const Eigen::VectorXd& x_new) {
        gn.trial_at(pr, d, x_new);
        ++out.evaluations;
        return gn.r_new.squaredNorm();
      },
      [&](const Eigen::VectorXd& h, double mu) { return h.dot(mu * h - gn.g); },
      [&](double F, double F_new) { return std::sqrt(F) - std::sqrt(F_new) <= ftol * std::sqrt(F); });
  out.f = de2000_cost(pr, d, x.data());  // the reported RMS, from delta_E_CIE2000 as every path
  ++out.evaluations;
}

// The mean loss Σ w_i ΔE_i / Σ w_i is a sum of Euclidean norms, ΔE_i = ‖q_i‖ with q_i the three
// squares of de2000_squares (J_i their Jacobian rows). Minimised by a reweighted, damped Gauss–Newton:
// at x, with e_i = max(‖q_i‖, δ) and u_i = q_i / e_i, the gradient is g = Σ (w_i / e_i) J_iᵀ q_i, and
// the curvature of ‖q_i + J_i h‖ at h = 0 is J_iᵀ (I − u_i u_iᵀ) J_i / e_i (Newton: no curvature
// along q_i), whereas Weiszfeld's iteratively reweighted least squares (Beck & Sabach 2015, "Weiszfeld's
// method: old and new results", JOTA 164) uses J_iᵀ J_i / e_i, a majoriser that converges linearly.
// We take half the radial term, H = Σ (w_i / e_i) J_iᵀ (I − ½ u_i u_iᵀ) J_i: positive definite like
// Weiszfeld's, and on the Passport patches 2–5× fewer iterations to the same minimum (within 1e-5
// ΔE00 of a run with xtol 1e-12, ftol 1e-15); the pure Newton curvature stalls at the loss's kinks
// (patches fitted exactly). Steps (H + μI) h = −g; gain ratio on the mean itself against the model's
// decrease −(gᵀh + ½ hᵀHh); damping and stopping tests as levenberg_marquardt (damped_gauss_newton).
// δ = 1e-9 ΔE00 keeps weights finite at an exactly fitted patch. Started from least squares,
// unbounded; evaluations counted as levenberg_marquardt.
void reweighted_lm(const Problem& pr, const De2000Data& d, const FitOptions& options, std::vector<double>& x,
                   Outcome& out) {
  const int nvar = static_cast<int>(x.size());
  const Eigen::Index n = pr.n;
  const int max_iter = options.de2000.max_evaluations > 0 ? std::max(1, options.de2000.max_evaluations / 4) : 500;
  const double ftol = options.de2000.ftol_rel;
  constexpr double delta = 1e-9;
  De2000Data du = d;  // unweighted residuals: q_i itself
  du.w.assign(n, 1.0);
  GaussNewtonScratch gn(n, nvar);
  Eigen::Map<Eigen::VectorXd> xv(x.data(), nvar);
  auto loss = [&](const Eigen::VectorXd& res) {  // Σ w_i ‖q_i‖ (not yet divided by Σ w)
    double s = 0;
    for (Eigen::Index i = 0; i < n; ++i) s += d.w[i] * res.segment<3>(3 * i).norm();
    return s;
  };
  auto linearise = [&]() {
    gn.linearise_at(pr, du, xv);
    out.evaluations += 4;
    for (Eigen::Index i = 0; i < n; ++i) {  // A = Σ a_i J_iᵀ P_i J_i, g = Σ a_i J_iᵀ q_i
      const Vec3 q = gn.r.segment<3>(3 * i);
      const double e = std::max(q.norm(), delta);
      const double a = d.w[i] / e;
      const Vec3 ui = q / e;
      const Mat3 P = Mat3::Identity() - 0.5 * ui * ui.transpose();
      const Mat3& Gi = gn.G[static_cast<std::size_t>(i)];
      const Mat3 Mi = a * (Gi.transpose() * (P * Gi));
      gn.M.row(i) << Mi(0, 0), Mi(0, 1), Mi(0, 2), Mi(1, 1), Mi(1, 2), Mi(2, 2);
      gn.u.row(i) = (a * (Gi.transpose() * q)).transpose();
    }
    normal_equations(pr, gn.M, gn.u, gn.acc, gn.A, gn.g);
    return loss(gn.r);
  };
  damped_gauss_newton(
      xv, gn.A, gn.g, max_iter, options.de2000.xtol_rel, out, linearise,
      [&](const Eigen::VectorXd& x_new) {
        gn.trial_at(pr, du, x_new);
        ++out.evaluations;
        return loss(gn.r_new);
      },
      [&](const Eigen::VectorXd& h, double) { return -(gn.g.dot(h) + 0.5 * h.dot(gn.A * h)); },  // decrease of the majoriser
      [&](double S, double S_new) { return S - S_new <= ftol * S; });
  out.f = de2000_cost(pr, d, x.data());  // the reported mean, from delta_E_CIE2000 as every path
  ++out.evaluations;
}

}  // namespace tristim::fit_detail

// The CIEDE2000 objective: mean (or RMS) weighted ΔE00 under a stated white, started from least
// squares. Its loss and residuals, and the choice of minimiser: the Gauss–Newton iterations of
// fit_de2000_gauss_newton.cpp by default, NLopt's derivative-free optimisers on request.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../detmath.hpp"
#include "../optimise/bounded.hpp"
#include "fit_de2000.hpp"
#include "tristim/error.hpp"

namespace tristim::fit_detail {

namespace {

// Patch i's predicted XYZ for the free coefficients x (z stored channel-major).
Vec3 predicted_XYZ(const Problem& pr, const double* x, Eigen::Index i) {
  Vec3 XYZ;
  for (int c = 0; c < 3; ++c) {
    double s = pr.base(i, c);
    const double* zc = x + c * pr.q;
    for (int j = 0; j < pr.q; ++j) s += pr.B(i, j) * zc[j];
    XYZ[c] = s;
  }
  return XYZ;
}

// ΔE00² as a sum of three squares: with the components of eq (22) (ρ = RT/2, |ρ| ≤ 1),
// dL² + dC² + dH² + RT·dC·dH = dL² + (dC + ρ·dH)² + (1 - ρ²)·dH². Unlike ΔE itself (a norm, whose
// curvature Gauss–Newton would ignore), these are nearly linear in Lab, so Gauss–Newton converges fast.
Vec3 de2000_squares(const Vec3& Lab_ref, const Vec3& Lab) {
  const DeltaE2000 e = delta_E_CIE2000_components(Lab_ref, Lab);
  const double rho = 0.5 * e.RT;
  return Vec3(e.dL, e.dC + rho * e.dH, std::sqrt(std::max(0.0, 1.0 - rho * rho)) * e.dH);
}

}  // namespace

double de2000_cost(const Problem& pr, const De2000Data& d, const double* x) {
  // x: z stored channel-major (z(:,0), z(:,1), z(:,2)).
  double total = 0;
  for (Eigen::Index i = 0; i < pr.n; ++i) {
    const Vec3 XYZ = predicted_XYZ(pr, x, i);
    const Vec3 Lab = XYZ_to_Lab(XYZ, d.white);
    const double dE = delta_E_CIE2000(d.Lab_ref.row(i).transpose(), Lab);
    const double e = std::isfinite(dE) ? dE : 1e6;
    total += d.w[i] * (d.rms ? e * e : e);
  }
  return d.rms ? std::sqrt(total / d.wsum) : total / d.wsum;
}

// Residuals of patch i at x (channel-major z), weighted by sqrt(w_i): rows 3i..3i+2 of r. With G,
// also G[i] = ∂r_i/∂XYZ_i (3 × 3): ∂/∂Lab by forward differences of de2000_squares (step 1e-6 in
// Lab units, where ΔE ~ 1: truncation and rounding errors both ~1e-6 relative), chained through the
// analytic ∂Lab/∂XYZ of CIE 15:2004 eqs (8.1)-(8.3) (f = t^(1/3), f' = f/(3t) above ε = (6/29)³,
// else κ/116). The Jacobian rows of patch i follow from ∂XYZ_c/∂z(j,c) = B(i,j), since
// XYZ_c = base(i,c) + B(i,:)·z(:,c): J(3i + m, c·Q + j) = G[i](m, c)·B(i, j) (normal_equations).
// Non-finite values: residuals (1e6, 0, 0) as in de2000_cost, G[i] zero.
// qs: the unweighted squares q_i at x; with qs_at_x they are read from it (an earlier call at the
// same x wrote them: the trial point a linearisation follows), otherwise computed and written.
void de2000_residuals(const Problem& pr, const De2000Data& d, const double* x, Eigen::VectorXd& r,
                      std::vector<Mat3>* G, std::vector<Vec3>& qs, bool qs_at_x) {
  constexpr double h = 1e-6, eps = 216.0 / 24389.0, kappa = 24389.0 / 27.0;
  qs.resize(static_cast<std::size_t>(pr.n));
  for (Eigen::Index i = 0; i < pr.n; ++i) {
    const Vec3 XYZ = predicted_XYZ(pr, x, i);
    const Vec3 Lab = XYZ_to_Lab(XYZ, d.white);
    const Vec3 ref = d.Lab_ref.row(i).transpose();
    Vec3& qi = qs[static_cast<std::size_t>(i)];
    if (!qs_at_x) qi = de2000_squares(ref, Lab);
    const Vec3 q = qi;
    const double sw = std::sqrt(d.w[i]);
    const bool finite = q.allFinite();
    r.segment<3>(3 * i) = finite ? Vec3(sw * q) : Vec3(sw * 1e6, 0, 0);
    if (!G) continue;
    Mat3 dq_dLab;  // column k: ∂q/∂Lab_k
    // L* enters eqs (8), (12) and (18) only: moving it changes dL = ΔL'/S_L and leaves dC, dH and
    // R_T as they were, so column 0 is the difference of dL alone (the other two are exactly 0).
    dq_dLab.col(0) = Vec3((delta_E_CIE2000_dL(ref[0], Lab[0] + h) - q[0]) / h, 0, 0);
    for (int k = 1; k < 3; ++k) {
      Vec3 Lab_h = Lab;
      Lab_h[k] += h;
      dq_dLab.col(k) = (de2000_squares(ref, Lab_h) - q) / h;
    }
    double fp[3];  // d f(XYZ_c / white_c) / d XYZ_c
    for (int c = 0; c < 3; ++c) {
      const double t = XYZ[c] / d.white[c];
      fp[c] = (t > eps ? detmath::cbrt(t) / (3.0 * t) : kappa / 116.0) / d.white[c];
    }
    Mat3 dLab_dXYZ;  // L = 116 fy - 16, a = 500 (fx - fy), b = 200 (fy - fz)
    dLab_dXYZ << 0, 116.0 * fp[1], 0, 500.0 * fp[0], -500.0 * fp[1], 0, 0, 200.0 * fp[1], -200.0 * fp[2];
    Mat3& Gi = (*G)[static_cast<std::size_t>(i)];
    Gi = sw * dq_dLab * dLab_dXYZ;  // G(m, c) = ∂r_m/∂XYZ_c
    if (!finite || !Gi.allFinite()) Gi.setZero();
  }
}

Outcome minimise_de2000(const Problem& pr, const FitOptions& options, Eigen::MatrixXd& z) {
  Outcome out;
  const int nvar = pr.q * 3;
  De2000Data d;
  d.pr = &pr;
  d.white = options.white;
  d.rms = options.de2000.rms;
  if (!(d.white.minCoeff() > 0) || !d.white.allFinite())
    throw Error(ErrorCode::InvalidArgument, "CIEDE2000 objective: the white must be positive XYZ");
  d.Lab_ref.resize(pr.n, 3);
  for (Eigen::Index i = 0; i < pr.n; ++i) d.Lab_ref.row(i) = XYZ_to_Lab(pr.Y.row(i).transpose(), d.white).transpose();
  if (!options.weights.empty()) {
    if (static_cast<Eigen::Index>(options.weights.size()) != pr.n)
      throw Error(ErrorCode::PatchMismatch, "CIEDE2000 objective: " + std::to_string(options.weights.size()) +
                                                " weights for " + std::to_string(pr.n) + " patches");
    for (double w : options.weights)
      if (!(w >= 0) || !std::isfinite(w))
        throw Error(ErrorCode::InvalidArgument, "CIEDE2000 objective: weights must be finite and >= 0");
    d.w = options.weights;
  } else {
    d.w.assign(pr.n, 1.0);
  }
  d.wsum = 0;
  for (double w : d.w) d.wsum += w;
  if (!(d.wsum > 0)) throw Error(ErrorCode::InvalidArgument, "CIEDE2000 objective: all weights are zero");

  std::vector<double> x(nvar), lb(nvar), ub(nvar), step(nvar);
  for (int c = 0; c < 3; ++c) {
    double sc = pr.Y.col(c).norm();
    if (!(sc > 0)) sc = 1;
    for (int j = 0; j < pr.q; ++j) {
      const int v = c * pr.q + j;
      x[v] = z(j, c);
      const double half = std::fabs(x[v]) + sc;
      lb[v] = x[v] - half;
      ub[v] = x[v] + half;
      step[v] = options.de2000.initial_step * sc;
    }
  }
  out.f0 = de2000_cost(pr, d, x.data());
  if (out.f0 == 0) {  // already exact (a planted solution): nothing to improve
    out.f = 0;
    return out;
  }
  const auto set_z = [&](const std::vector<double>& v) {  // v: z channel-major, as x
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < pr.q; ++j) z(j, c) = v[c * pr.q + j];
  };
  const std::string& alg = options.de2000.algorithm;
  if (alg == "lm" || alg == "irls" || alg == "auto") {  // "auto": lm for the RMS, irls for the mean
    const bool lm = alg == "lm" || (alg == "auto" && d.rms);
    if (lm != d.rms)
      throw Error(ErrorCode::InvalidArgument,
                  lm ? "CIEDE2000 objective: algorithm 'lm' minimises a sum of squares and needs the RMS loss"
                     : "CIEDE2000 objective: algorithm 'irls' minimises the mean; the RMS loss uses 'lm'");
    if (lm) levenberg_marquardt(pr, d, options, x, out);
    else reweighted_lm(pr, d, options, x, out);
    set_z(x);
    return out;
  }
  const std::optional<optimise::Algorithm> a = optimise::algorithm_from_id(alg);
  if (!a)
    throw Error(ErrorCode::UnknownId, "CIEDE2000 objective: unknown algorithm '" + alg +
                                          "' (auto, lm, irls, bobyqa, sbplx, newuoa, praxis, cobyla, neldermead)");
  optimise::BoundedOptions bounded;
  bounded.algorithm = *a;
  bounded.lower = std::move(lb);
  bounded.upper = std::move(ub);
  bounded.initial_step = std::move(step);
  bounded.xtol_rel = options.de2000.xtol_rel;
  bounded.ftol_rel = options.de2000.ftol_rel;
  bounded.max_evaluations = options.de2000.max_evaluations > 0 ? options.de2000.max_evaluations : 200 * nvar;
  // PRAXIS perturbs its search with NLopt's random numbers, which NLopt seeds from the clock
  // unless told: without a fixed seed every run took other steps (348 or 350 evaluations, the
  // 11th digit moving). The generator's state is per thread natively (one compare row
  // per thread) and global in the single-threaded wasm module.
  bounded.seed = 20130401;
  // The fit keeps the best point evaluated (the start unless a point beat it), whatever NLopt returns.
  double best = out.f0;
  std::vector<double> best_x = x;
  const optimise::BoundedMinimum m = optimise::minimise_bounded(
      [&](const double* v) {
        const double f = de2000_cost(pr, d, v);
        if (f < best) {
          best = f;
          best_x.assign(v, v + nvar);
        }
        return f;
      },
      x, bounded);
  if (m.failed && best >= out.f0 && m.evaluations == 0) throw Error(ErrorCode::FitFailed, m.message);
  set_z(best_x);
  out.f = best;
  out.evaluations = m.evaluations;
  out.iterations = m.evaluations;
  out.hit_limit = m.hit_limit;
  return out;
}

}  // namespace tristim::fit_detail

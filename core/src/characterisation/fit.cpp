// Fitting: least squares (QR), Guarnera's pattern search (Algorithm 2), mean CIEDE2000 (reweighted
// Levenberg–Marquardt; NLopt on request), RMS CIEDE2000 (Levenberg–Marquardt), optional white-point preservation (equality constraint, null-space parametrisation).
#include <nlopt.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "../detmath.hpp"
#include "tristim/error.hpp"
#include "tristim/characterisation/models.hpp"

namespace tristim {

const char* objective_id(Objective objective) {
  switch (objective) {
    case Objective::LeastSquares: return "ls";
    case Objective::PatternSearch: return "psm";
    case Objective::DeltaE2000: return "de2000";
  }
  return "?";
}

Objective objective_from_id(const std::string& id) {
  if (id == "ls" || id == "least-squares") return Objective::LeastSquares;
  if (id == "psm" || id == "pattern-search") return Objective::PatternSearch;
  if (id == "de2000" || id == "ciede2000") return Objective::DeltaE2000;
  throw Error(ErrorCode::UnknownId, "unknown objective '" + id + "' (expected ls, psm or de2000)");
}

std::vector<std::string> objective_ids() { return {"ls", "psm", "de2000"}; }

const char* fit_status_name(FitStatus status) {
  switch (status) {
    case FitStatus::Ok: return "ok";
    case FitStatus::IllConditioned: return "ill_conditioned";
    case FitStatus::ExactlyDetermined: return "exactly_determined";
    case FitStatus::IterationLimit: return "iteration_limit";
  }
  return "?";
}

void validate_patches(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ) {
  if (camera_RGB.rows() != reference_XYZ.rows())
    throw Error(ErrorCode::PatchMismatch, "camera RGB has " + std::to_string(camera_RGB.rows()) +
                                              " patches but reference XYZ has " +
                                              std::to_string(reference_XYZ.rows()));
  if (camera_RGB.rows() == 0) throw Error(ErrorCode::TooFewPatches, "no patches to fit");
  static const char* rgb_names[3] = {"R", "G", "B"};
  static const char* xyz_names[3] = {"X", "Y", "Z"};
  for (Eigen::Index i = 0; i < camera_RGB.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(camera_RGB(i, c)))
        throw Error(ErrorCode::NonFinite, "camera RGB patch " + std::to_string(i + 1) + " channel " +
                                              rgb_names[c] + " is not finite");
      if (!std::isfinite(reference_XYZ(i, c)))
        throw Error(ErrorCode::NonFinite, "reference XYZ patch " + std::to_string(i + 1) + " " +
                                              xyz_names[c] + " is not finite");
      if (reference_XYZ(i, c) < 0)
        throw Error(ErrorCode::NegativeValue, "reference XYZ patch " + std::to_string(i + 1) + " " +
                                                  xyz_names[c] + " is negative");
    }
}

namespace {

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

Problem make_problem(const ModelInfo& info, const PatchMatrix& rgb, const PatchMatrix& xyz,
                     const FitOptions& options) {
  validate_patches(rgb, xyz);
  if (options.preserve_white) {
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(options.white_RGB[c]) || !std::isfinite(options.white_XYZ[c]))
        throw Error(ErrorCode::NonFinite, "white-point preservation: white RGB/XYZ not finite");
  }
  Problem pr;
  pr.info = &info;
  pr.n = rgb.rows();
  pr.p = info.n_terms;
  pr.constrained = options.preserve_white;
  pr.q = pr.p - (pr.constrained ? 1 : 0);
  if (pr.n < pr.q)
    throw Error(ErrorCode::TooFewPatches,
                "model '" + info.id + "' has " + std::to_string(pr.q) + " free coefficients per channel but only " +
                    std::to_string(pr.n) + " patches were given");
  // A constant channel makes every model meaningless (and collinear with any offset term).
  static const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    const double lo = rgb.col(c).minCoeff(), hi = rgb.col(c).maxCoeff();
    const double mag = std::max(std::fabs(lo), std::fabs(hi));
    if (pr.n > 1 && hi - lo <= 1e-12 * std::max(mag, 1e-300))
      throw Error(ErrorCode::IllConditioned,
                  std::string("camera channel ") + names[c] + " is constant over all " +
                      std::to_string(pr.n) + " patches");
  }
  Eigen::MatrixXd A(pr.n, pr.p);
  for (Eigen::Index i = 0; i < pr.n; ++i) {
    double phi[kMaxModelTerms];
    expand(info, rgb(i, 0), rgb(i, 1), rgb(i, 2), phi);
    for (int j = 0; j < pr.p; ++j) A(i, j) = phi[j];
  }
  pr.s.resize(pr.p);
  for (int j = 0; j < pr.p; ++j) {
    const double norm = A.col(j).norm();
    if (!(norm > 0) || !std::isfinite(norm))
      throw Error(ErrorCode::IllConditioned,
                  "term " + info.term_names[j] + " of model '" + info.id + "' is zero on every patch");
    pr.s[j] = 1.0 / norm;
  }
  pr.As = A * pr.s.asDiagonal();
  pr.Y = xyz;
  if (pr.constrained) {
    Eigen::VectorXd c(pr.p);
    expand(info, options.white_RGB[0], options.white_RGB[1], options.white_RGB[2], c.data());
    Eigen::VectorXd cs = c.cwiseProduct(pr.s);  // constraint in equilibrated coordinates
    const double cn = cs.squaredNorm();
    if (!(cn > 0))
      throw Error(ErrorCode::IllConditioned, "white-point preservation: the white RGB expands to zero");
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(cs);
    Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(pr.p, pr.p);
    pr.Z = Q.rightCols(pr.q);
    pr.Xp = cs * options.white_XYZ.transpose() / cn;
  } else {
    pr.Z = Eigen::MatrixXd::Identity(pr.p, pr.p);
    pr.Xp = Eigen::MatrixXd::Zero(pr.p, 3);
  }
  if (pr.constrained) {
    pr.B = pr.As * pr.Z;
    pr.base = pr.As * pr.Xp;
  } else {
    // Z = I, Xp = 0: the products are A_s and 0 exactly (each sum has one non-zero term), so skip
    // them (in wasm Eigen's GEMM is scalar code; these two products were a fifth of a 3×3 fit).
    // "+ 0.0" turns a −0 into +0 as the GEMM's zero-initialised accumulator did.
    pr.B = pr.As.array() + 0.0;
    pr.base = Eigen::MatrixXd::Zero(pr.n, 3);
  }
  return pr;
}

// Least squares in the free coordinates; returns z (Q × 3) and the condition number.
Eigen::MatrixXd solve_ls(const Problem& pr, const FitOptions& options, double& cond) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(pr.B);
  Eigen::MatrixXd R = qr.matrixQR().topRows(pr.q).triangularView<Eigen::Upper>();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(R);
  const auto& sv = svd.singularValues();
  const double smax = sv(0), smin = sv(sv.size() - 1);
  cond = smin > 0 ? smax / smin : INFINITY;
  if (!(cond <= options.max_condition)) {
    std::ostringstream ss;
    ss << "model '" << pr.info->id << "': the design matrix is singular or nearly so (condition number "
       << cond << " > " << options.max_condition
       << "); collinear camera RGB (e.g. only grey patches) or too many terms for these patches";
    throw Error(ErrorCode::IllConditioned, ss.str());
  }
  return qr.solve(pr.Y - pr.base);
}

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

struct PsmOutcome {
  int iterations = 0, evaluations = 0;
  double f0 = 0, f = 0;
  bool hit_limit = false;
};

// Guarnera 2018 Algorithm 2 on z (Q × 3), coordinate directions ±e, opportunistic poll.
PsmOutcome pattern_search(const Problem& pr, const PatternSearchOptions& o, Eigen::MatrixXd& z) {
  PsmOutcome out;
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

struct De2000Data {
  const Problem* pr;
  Eigen::MatrixXd Lab_ref;  // N × 3
  std::vector<double> w;
  double wsum;
  Vec3 white;
  bool rms = false;
  int evaluations = 0;
  double best = INFINITY;
  std::vector<double> best_x;
};

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

double nlopt_objective(unsigned n, const double* x, double* grad, void* data) {
  (void)grad;
  auto* d = static_cast<De2000Data*>(data);
  const double f = de2000_cost(*d->pr, *d, x);
  ++d->evaluations;
  if (f < d->best) {
    d->best = f;
    d->best_x.assign(x, x + n);
  }
  return f;
}

struct De2000Outcome {
  int iterations = 0, evaluations = 0;
  double f0 = 0, f = 0;
  bool hit_limit = false;
};

// ΔE00² as a sum of three squares: with the components of eq (22) (ρ = RT/2, |ρ| ≤ 1),
// dL² + dC² + dH² + RT·dC·dH = dL² + (dC + ρ·dH)² + (1 - ρ²)·dH². Unlike ΔE itself (a norm, whose
// curvature Gauss–Newton would ignore), these are nearly linear in Lab, so Gauss–Newton converges fast.
Vec3 de2000_squares(const Vec3& Lab_ref, const Vec3& Lab) {
  const DeltaE2000 e = delta_E_CIE2000_components(Lab_ref, Lab);
  const double rho = 0.5 * e.RT;
  return Vec3(e.dL, e.dC + rho * e.dH, std::sqrt(std::max(0.0, 1.0 - rho * rho)) * e.dH);
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
                         double xtol, De2000Outcome& out, Linearise linearise, Trial trial, Predicted predicted,
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

// The RMS loss is a sum of squares, sqrt(Σ w_i ΔE_i² / Σ w_i): minimised by Levenberg–Marquardt on
// the 3N residuals of de2000_residuals (damped_gauss_newton with A = JᵀJ, g = Jᵀr, F = ‖r‖², the
// predicted decrease hᵀ(μh − g) = 2·(L(0) − L(h)), and a relative decrease of the RMS below
// ftol_rel), started from least squares, unbounded (the box of the derivative-free path is only its
// trust region). evaluations counts residual vectors (a linearisation counts 4: the residuals and
// one difference per Lab axis, as before the residuals at an accepted trial point were reused and
// the L* difference made cheap, so the limit max_evaluations / 4 iterations keeps its meaning).
void levenberg_marquardt(const Problem& pr, const De2000Data& d, const FitOptions& options, std::vector<double>& x,
                         De2000Outcome& out) {
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
                   De2000Outcome& out) {
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

De2000Outcome minimise_de2000(const Problem& pr, const FitOptions& options, Eigen::MatrixXd& z) {
  De2000Outcome out;
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
  d.best = out.f0;
  d.best_x = x;
  if (out.f0 == 0) {  // already exact (a planted solution): nothing to improve
    out.f = 0;
    return out;
  }
  const std::string& alg = options.de2000.algorithm;
  if (alg == "lm" || (alg == "auto" && d.rms)) {
    if (!d.rms)
      throw Error(ErrorCode::InvalidArgument,
                  "CIEDE2000 objective: algorithm 'lm' minimises a sum of squares and needs the RMS loss");
    levenberg_marquardt(pr, d, options, x, out);
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < pr.q; ++j) z(j, c) = x[c * pr.q + j];
    return out;
  }
  if (alg == "irls" || alg == "auto") {
    if (d.rms)
      throw Error(ErrorCode::InvalidArgument,
                  "CIEDE2000 objective: algorithm 'irls' minimises the mean; the RMS loss uses 'lm'");
    reweighted_lm(pr, d, options, x, out);
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < pr.q; ++j) z(j, c) = x[c * pr.q + j];
    return out;
  }
  nlopt_algorithm a;
  if (alg == "bobyqa") a = NLOPT_LN_BOBYQA;
  else if (alg == "sbplx") a = NLOPT_LN_SBPLX;
  else if (alg == "newuoa") a = NLOPT_LN_NEWUOA_BOUND;
  else if (alg == "praxis") a = NLOPT_LN_PRAXIS;
  else if (alg == "cobyla") a = NLOPT_LN_COBYLA;
  else if (alg == "neldermead") a = NLOPT_LN_NELDERMEAD;
  else throw Error(ErrorCode::UnknownId, "CIEDE2000 objective: unknown algorithm '" + alg + "' (auto, lm, irls, bobyqa, sbplx, newuoa, praxis, cobyla, neldermead)");
  nlopt_opt opt = nlopt_create(a, static_cast<unsigned>(nvar));
  if (!opt) throw Error(ErrorCode::FitFailed, "NLopt could not create the optimiser");
  nlopt_set_min_objective(opt, nlopt_objective, &d);
  nlopt_set_lower_bounds(opt, lb.data());
  nlopt_set_upper_bounds(opt, ub.data());
  nlopt_set_initial_step(opt, step.data());
  nlopt_set_xtol_rel(opt, options.de2000.xtol_rel);
  nlopt_set_ftol_rel(opt, options.de2000.ftol_rel);
  const int maxeval = options.de2000.max_evaluations > 0 ? options.de2000.max_evaluations : 200 * nvar;
  nlopt_set_maxeval(opt, maxeval);
  double minf = 0;
  // PRAXIS perturbs its search with NLopt's random numbers, which NLopt seeds from the clock
  // unless told: without a fixed seed every run took other steps (348 or 350 evaluations, the
  // 11th digit moving). The generator's state is per thread natively (one compare row
  // per thread) and global in the single-threaded wasm module.
  nlopt_srand(20130401);
  const nlopt_result res = nlopt_optimize(opt, x.data(), &minf);
  nlopt_destroy(opt);
  if (res < 0 && res != NLOPT_ROUNDOFF_LIMITED && d.best >= out.f0 && d.evaluations == 0)
    throw Error(ErrorCode::FitFailed, "NLopt failed with code " + std::to_string(static_cast<int>(res)));
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < pr.q; ++j) z(j, c) = d.best_x[c * pr.q + j];
  out.f = d.best;
  out.evaluations = d.evaluations;
  out.iterations = d.evaluations;
  out.hit_limit = res == NLOPT_MAXEVAL_REACHED;
  return out;
}

void add_message(FitResult& r, const std::string& m) {
  if (!r.message.empty()) r.message += "; ";
  r.message += m;
}

FitResult fit_info(const ModelInfo& info, const PatchMatrix& rgb, const PatchMatrix& xyz,
                   const FitOptions& options) {
  Problem pr = make_problem(info, rgb, xyz, options);
  FitResult r;
  r.model.id = info.id;
  r.objective = options.objective;
  r.white_preserved = options.preserve_white;
  double cond = 0;
  Eigen::MatrixXd z = solve_ls(pr, options, cond);
  r.condition_number = cond;
  if (options.objective == Objective::PatternSearch) {
    const PsmOutcome o = pattern_search(pr, options.psm, z);
    r.iterations = o.iterations;
    r.evaluations = o.evaluations;
    r.start_objective_value = o.f0;
    r.objective_value = o.f;
    if (o.hit_limit) {
      r.status = FitStatus::IterationLimit;
      add_message(r, "pattern search stopped at its iteration limit (" + std::to_string(o.iterations) + ")");
    }
  } else if (options.objective == Objective::DeltaE2000) {
    const De2000Outcome o = minimise_de2000(pr, options, z);
    r.iterations = o.iterations;
    r.evaluations = o.evaluations;
    r.start_objective_value = o.f0;
    r.objective_value = o.f;
    if (o.hit_limit) {
      r.status = FitStatus::IterationLimit;
      add_message(r, "CIEDE2000 optimiser stopped at its limit (" + std::to_string(o.iterations) + " iterations, " +
                         std::to_string(o.evaluations) + " evaluations)");
    }
  }
  r.model.coefficients = pr.coefficients(z);
  r.fitted = predict(r.model, rgb);
  r.residuals = r.fitted - xyz;
  if (options.objective == Objective::LeastSquares) {
    r.objective_value = std::sqrt(r.residuals.squaredNorm() / (3.0 * static_cast<double>(pr.n)));
    r.start_objective_value = r.objective_value;
  }
  if (cond > options.warn_condition) {
    if (r.status == FitStatus::Ok) r.status = FitStatus::IllConditioned;
    std::ostringstream ss;
    ss << "condition number " << cond << " > " << options.warn_condition
       << ": coefficients are poorly determined by these patches; trust held-out errors only";
    add_message(r, ss.str());
  }
  if (pr.n == pr.q) {
    if (r.status == FitStatus::Ok) r.status = FitStatus::ExactlyDetermined;
    add_message(r, "as many patches as free coefficients: the training error is zero by construction");
  }
  return r;
}

// A fold that leaves out row k must refuse what a refit would refuse: a camera channel that is
// constant over the remaining patches (make_problem's check).
void check_fold_channels(const PatchMatrix& rgb, Eigen::Index k) {
  static const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    double lo = INFINITY, hi = -INFINITY;
    for (Eigen::Index i = 0; i < rgb.rows(); ++i)
      if (i != k) lo = std::min(lo, rgb(i, c)), hi = std::max(hi, rgb(i, c));
    const double mag = std::max(std::fabs(lo), std::fabs(hi));
    if (hi - lo <= 1e-12 * std::max(mag, 1e-300))
      throw Error(ErrorCode::IllConditioned, std::string("leaving out patch ") + std::to_string(k + 1) +
                                                 " makes camera channel " + names[c] + " constant");
  }
}

}  // namespace

PatchMatrix leave_one_out_least_squares(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                                        const FitOptions& options, int white_patch_index) {
  const ModelInfo& info = model_info(model_id);
  FitOptions o = options;
  o.objective = Objective::LeastSquares;
  const Problem pr = make_problem(info, rgb, xyz, o);
  if (pr.n - 1 < std::max(pr.q, 1))
    throw Error(ErrorCode::TooFewPatches, "leave-one-out: " + std::to_string(pr.n - 1) + " patches cannot fit '" +
                                              info.id + "' (" + std::to_string(pr.q) + " free coefficients)");
  double cond = 0;
  const Eigen::MatrixXd z = solve_ls(pr, o, cond);
  const Eigen::MatrixXd E = pr.Y - pr.predictions(z);  // N × 3 training residuals
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(pr.B);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(pr.n, pr.q);  // thin Q: H = Q·Qᵀ
  PatchMatrix out(pr.n, 3);
  for (Eigen::Index k = 0; k < pr.n; ++k) {
    check_fold_channels(rgb, k);
    if (k == white_patch_index && o.preserve_white) {
      // The white patch's own fold is fitted without the constraint (it may not see its patch).
      FitOptions u = o;
      u.preserve_white = false;
      u.warn_condition = INFINITY;
      PatchMatrix r(pr.n - 1, 3), x(pr.n - 1, 3);
      for (Eigen::Index i = 0, j = 0; i < pr.n; ++i)
        if (i != k) r.row(j) = rgb.row(i), x.row(j++) = xyz.row(i);
      out.row(k) = predict(fit_info(info, r, x, u).model, Vec3(rgb.row(k).transpose())).transpose();
      continue;
    }
    // PRESS residual (Allen 1974): the fold without patch k predicts y_k − e_k / (1 − h_kk). With the
    // white constraint the fit is unconstrained least squares in the null-space coordinates (B, z),
    // so the same identity holds there.
    const double leverage = Q.row(k).squaredNorm();
    if (!(1 - leverage > 1e-10))
      throw Error(ErrorCode::IllConditioned, "leaving out patch " + std::to_string(k + 1) +
                                                 " leaves model '" + info.id + "' undetermined (leverage 1)");
    out.row(k) = pr.Y.row(k) - E.row(k) / (1 - leverage);
  }
  return out;
}

FitResult fit(const std::string& model_id, const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
              const FitOptions& options) {
  return fit_info(model_info(model_id), camera_RGB, reference_XYZ, options);
}

FitResult fit_matrix_3x3(const PatchMatrix& rgb, const PatchMatrix& xyz, const FitOptions& options) {
  return fit("matrix-3x3", rgb, xyz, options);
}
FitResult fit_matrix_3x4(const PatchMatrix& rgb, const PatchMatrix& xyz, const FitOptions& options) {
  return fit("matrix-3x4", rgb, xyz, options);
}
FitResult fit_Shen2008(const PatchMatrix& rgb, const PatchMatrix& xyz, const FitOptions& options) {
  return fit("Shen2008", rgb, xyz, options);
}
FitResult fit_Cheung2004(const PatchMatrix& rgb, const PatchMatrix& xyz, int terms, const FitOptions& options) {
  return fit("Cheung2004-" + std::to_string(terms), rgb, xyz, options);
}
FitResult fit_Finlayson2015(const PatchMatrix& rgb, const PatchMatrix& xyz, int degree,
                            const FitOptions& options) {
  if (degree < 1 || degree > 4)
    throw Error(ErrorCode::InvalidArgument, "root-polynomial degree " + std::to_string(degree) + " is not 1..4");
  return fit("Finlayson2015-" + std::to_string(degree), rgb, xyz, options);
}
FitResult fit_Guarnera2018(const PatchMatrix& rgb, const PatchMatrix& xyz, const std::string& transform,
                           const FitOptions& options) {
  if (transform != "T1" && transform != "To" && transform != "T2R")
    throw Error(ErrorCode::UnknownId, "Guarnera 2018 transform '" + transform + "' (expected T1, To, T2R)");
  return fit("Guarnera2018-" + transform, rgb, xyz, options);
}

}  // namespace tristim

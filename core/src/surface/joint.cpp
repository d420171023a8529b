// Phase II (Abed, Berns & Masaoka 2013, Figure 3): surface coefficients jointly with an anchored
// 3×3 matrix; and the "corrected 3×3" of eqs (6)-(13), Appendix C.
#include "tristim/surface/joint.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "../sum4.hpp"
#include "correction.hpp"
#include "minimise.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/error.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

namespace {

using surface_detail::PointCorrection;

void check_rgb(const PatchMatrix& rgb, const std::string& what) {
  for (Eigen::Index i = 0; i < rgb.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(rgb(i, c)))
        throw Error(ErrorCode::InvalidArgument, what + ": patch " + std::to_string(i + 1) + " is not finite");
}

// The Figure 3 problem with the matrix solved in closed form for any reference XYZ.
struct JointProblem {
  Eigen::MatrixXd rgb;         // N × 3
  Eigen::MatrixXd Rm;          // N × L instrument reflectances
  Eigen::MatrixXd T;           // L × 3: XYZ row = R row · T (the integration rule is linear)
  Mat3 G_inv;                  // (RGBᵀ RGB)⁻¹
  bool anchored = true;
  Eigen::Vector3d w, g;        // white RGB, G_inv·w
  double s = 1;                // wᵀ G_inv w
  Eigen::Vector3d white_XYZ;

  // Least-squares matrix for reference XYZ (N × 3), with M·w = white_XYZ when anchored.
  Mat3 matrix_for(const Eigen::MatrixXd& X) const {
    Mat3 XtRGB;  // Xᵀ·RGB, each entry summed over the patches by sum4
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        XtRGB(a, b) = sum4(X.rows(), [&](Eigen::Index i) { return X(i, a) * rgb(i, b); });
    Mat3 M = XtRGB * G_inv;  // M_ls = Xᵀ·RGB·(RGBᵀRGB)⁻¹
    if (anchored) M += (white_XYZ - M * w) * g.transpose() / s;  // the equality-constrained solution
    return M;
  }
  // (p applied to Rm) · T, written as column updates rather than through Eigen's product: X(i, j)
  // is the sum over wavelengths in order, the same in both builds, and the innermost loop runs
  // over patches (contiguous, independent), which the compilers vectorise (SSE2 natively, SIMD128
  // in wasm). Each corrected column is formed once, in a buffer, never as an N × L matrix.
  Eigen::MatrixXd integrate(const PointCorrection& p) const {
    const Eigen::Index n = Rm.rows();
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, 3);
    Eigen::VectorXd column(n);
    for (Eigen::Index k = 0; k < Rm.cols(); ++k) {
      const double* r = Rm.col(k).data();
      double* q = column.data();
      for (Eigen::Index i = 0; i < n; ++i) q[i] = p.value(r[i]);
      for (int j = 0; j < 3; ++j) {
        const double t = T(k, j);
        double* x = X.col(j).data();
        for (Eigen::Index i = 0; i < n; ++i) x[i] += q[i] * t;
      }
    }
    return X;
  }
  // The affine corrections (none, scaler, offset, scaler-offset: R' = a R + b, eq 5) commute with
  // the linear integration: (a Rm + b)·T = a (Rm·T) + b (1·T). prepare() forms Rm·T (`RT`, also
  // the report's uncorrected XYZ) and T's column sums (`Tsum`) once, so such an evaluation costs
  // N × 3 operations instead of N × L × 4 (equal to integrate() up to rounding).
  Eigen::MatrixXd RT;
  Eigen::Vector3d Tsum = Eigen::Vector3d::Zero();
  void prepare() {
    RT = integrate(PointCorrection{});  // identity: a = 1, b = 0
    for (Eigen::Index k = 0; k < T.rows(); ++k)
      for (int j = 0; j < 3; ++j) Tsum[j] += T(k, j);
  }
  // XYZ of the corrected reflectances (needs prepare() for the affine kinds).
  Eigen::MatrixXd corrected_XYZ(PointCorrection::Kind kind, const std::vector<double>& c) const {
    const PointCorrection p = surface_detail::prepare_correction(kind, c);
    if (kind == PointCorrection::Saunderson) return integrate(p);
    const Eigen::Index n = Rm.rows();
    Eigen::MatrixXd X(n, 3);
    for (int j = 0; j < 3; ++j) {
      const double* rt = RT.col(j).data();
      const double bt = p.b * Tsum[j];
      double* x = X.col(j).data();
      for (Eigen::Index i = 0; i < n; ++i) x[i] = p.a * rt[i] + bt;
    }
    return X;
  }
  // Σ over patches and X, Y, Z of (M·rgb − X)², by sum4 per column.
  double cost(const Eigen::MatrixXd& X) const {
    const Mat3 M = matrix_for(X);
    double total = 0;
    for (int c = 0; c < 3; ++c)
      total += sum4(X.rows(), [&](Eigen::Index i) {
        const double e = rgb(i, 0) * M(c, 0) + rgb(i, 1) * M(c, 1) + rgb(i, 2) * M(c, 2) - X(i, c);
        return e * e;
      });
    return total;
  }
};

}  // namespace

JointFitResult fit_surface_joint_Abed2013(const MethodChoice& start, const PatchMatrix& camera_RGB,
                                          const SpectralData& reflectances, const JointFitOptions& options) {
  const SurfaceMethod& row = surface_method(start.method);
  const MethodChoice first = complete_choice(row.info, start);
  if (first.settings.count("spectral") && !first.settings.at("spectral").empty())
    throw Error(ErrorCode::InvalidArgument, "the joint fit (Phase II) fits wavelength-independent coefficients; "
                                            "drop the 'spectral' option");
  check_reflectances(reflectances, "training reflectances");
  const Eigen::Index n = camera_RGB.rows();
  if (static_cast<size_t>(n) != reflectances.size())
    throw Error(ErrorCode::PatchMismatch, "camera RGB has " + std::to_string(n) + " patches but the reflectances " +
                                              std::to_string(reflectances.size()));
  if (n < 3) throw Error(ErrorCode::TooFewPatches, "the joint fit needs at least 3 patches for the 3×3 matrix");
  check_rgb(camera_RGB, "camera RGB");
  if (options.anchor_white) {
    if (!options.white_RGB.allFinite() || !(options.white_RGB.norm() > 0))
      throw Error(ErrorCode::InvalidArgument,
                  "the joint fit is anchored to a white reference: give the camera RGB of a Lambertian white (PTFE) "
                  "in the capture geometry (white_RGB)");
    if (!(options.white_reflectance > 0 && options.white_reflectance <= 1.5))
      throw Error(ErrorCode::InvalidArgument, "white reference reflectance must be in (0, 1.5]");
  }

  JointProblem pr;
  pr.rgb = camera_RGB;
  const size_t L = reflectances.wavelengths.size();
  pr.Rm.resize(n, static_cast<Eigen::Index>(L));
  for (Eigen::Index i = 0; i < n; ++i)
    for (size_t w = 0; w < L; ++w) pr.Rm(i, static_cast<Eigen::Index>(w)) = reflectances.values[static_cast<size_t>(i)][w];
  const SpectralData illuminant = options.illuminant.size() ? options.illuminant : illuminant_spd("D50");
  pr.T = surface_detail::integration_matrix(reflectances.wavelengths, reflectances.linear, illuminant, options.observer);
  Mat3 G;  // RGBᵀRGB
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) G(a, b) = sum4(n, [&](Eigen::Index i) { return camera_RGB(i, a) * camera_RGB(i, b); });
  Eigen::JacobiSVD<Mat3> svd(G);
  const double cond = svd.singularValues()(0) / std::max(svd.singularValues()(2), 1e-300);
  if (!(cond < 1e14))
    throw Error(ErrorCode::IllConditioned, "the camera RGB of the training patches are collinear (condition number of "
                                           "RGBᵀRGB " + std::to_string(cond) + ")");
  pr.G_inv = G.inverse();
  pr.anchored = options.anchor_white;
  pr.white_XYZ = options.white_reflectance * illuminant_white_XYZ(illuminant, options.observer);
  if (pr.anchored) {
    pr.w = options.white_RGB;
    pr.g = pr.G_inv * pr.w;
    pr.s = pr.w.dot(pr.g);
  }

  const PointCorrection::Kind kind = surface_detail::correction_kind(row.info.id);
  pr.prepare();  // Rm·T: the affine corrections' evaluations and the report's uncorrected XYZ
  const std::vector<size_t> free = free_coefficients(row.info.id, options.free);
  std::vector<double> base(row.coefficients.size()), lb, ub;
  for (size_t j = 0; j < row.coefficients.size(); ++j) base[j] = choice_number(first, row.coefficients[j]);
  for (size_t j : free)
    for (const auto& o : row.info.options)
      if (o.name == row.coefficients[j]) { lb.push_back(o.min); ub.push_back(o.max); }
  auto full = [&](const double* x) {
    std::vector<double> c = base;
    for (size_t i = 0; i < free.size(); ++i) c[free[i]] = x[i];
    return c;
  };
  auto f = [&](const double* x) {
    try {
      return pr.cost(pr.corrected_XYZ(kind, full(x)));
    } catch (const Error&) {  // singular Saunderson coefficients
      return HUGE_VAL;
    }
  };
  auto pick = [&](const std::vector<double>& c) {
    std::vector<double> x;
    for (size_t j : free) x.push_back(c[j]);
    return x;
  };
  std::vector<std::vector<double>> starts = {pick(base)};
  if (row.info.id == "saunderson") {
    // The scaler-offset optimum of this same problem, read back through Appendix B (correction.hpp).
    JointFitOptions so_options = options;
    so_options.free = "capture";
    const JointFitResult so = fit_surface_joint_Abed2013({"scaler-offset", {}, {}}, camera_RGB, reflectances, so_options);
    starts.clear();
    for (const auto& c : surface_detail::saunderson_starts(base, free, choice_number(so.choice, "mu"),
                                                         choice_number(so.choice, "rho")))
      starts.push_back(pick(c));
  }

  JointFitResult r;
  for (size_t j : free) r.free.push_back(row.coefficients[j]);
  r.dE_xyz_rms_start = std::sqrt(f(pick(base).data()) / static_cast<double>(n));
  const surface_detail::Minimum m =
      surface_detail::minimise_from_starts(f, starts, lb, ub, options.max_evaluations, "joint surface fit (" + row.info.id + ")");
  const std::vector<double> c = full(m.x.data());
  r.choice = surface_choice(row.info.id, c);
  r.evaluations = m.evaluations;
  const Eigen::MatrixXd X = pr.corrected_XYZ(kind, c);
  r.matrix = pr.matrix_for(X);
  r.corrected_XYZ = X;
  r.reference_XYZ = pr.RT;  // Rm·T
  r.fitted_XYZ = camera_RGB * r.matrix.transpose();
  r.dE_xyz_rms = std::sqrt((r.fitted_XYZ - r.corrected_XYZ).rowwise().squaredNorm().mean());
  std::string at_bound;
  for (size_t i = 0; i < free.size(); ++i)
    if (c[free[i]] <= lb[i] + 1e-9 || c[free[i]] >= ub[i] - 1e-9)
      at_bound += (at_bound.empty() ? "" : ", ") + row.coefficients[free[i]];
  if (m.hit_limit) {
    r.status = "iteration_limit";
    r.message = "the optimiser stopped at its evaluation limit";
  } else if (!at_bound.empty()) {
    r.status = "at_bound";
    r.message = "coefficient(s) on a bound of the table: " + at_bound;
  }
  return r;
}

CorrectedMatrix fit_corrected_3x3_Abed2013(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                                           const Vec3& white_RGB, const Vec3& white_XYZ) {
  if (!white_RGB.allFinite() || !white_XYZ.allFinite())
    throw Error(ErrorCode::InvalidArgument, "corrected 3×3: white RGB / XYZ must be finite");
  const FitResult fit34 = fit_matrix_3x4(camera_RGB, reference_XYZ);  // eq (26), step 4
  CorrectedMatrix out;
  out.matrix_3x4 = fit34.model.coefficients;
  out.matrix_prime = out.matrix_3x4.leftCols<3>();  // step 5: omit the offset column
  const Vec3 v = out.matrix_prime * white_RGB;
  if (!(v.squaredNorm() > 0))
    throw Error(ErrorCode::IllPosed, "corrected 3×3: M'·RGB_w is zero, μ of eq (12) is undefined");
  out.mu = v.dot(white_XYZ) / v.squaredNorm();  // eq (12): the pseudo-inverse of a 3 × 1 vector
  out.matrix = out.mu * out.matrix_prime;       // eq (13)
  return out;
}

}  // namespace tristim

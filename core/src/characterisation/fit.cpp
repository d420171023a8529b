// The fit dispatcher (fit.hpp): validation, the equilibrated problem with optional white-point
// preservation (equality constraint, null-space parametrisation), then one objective family —
// least squares (fit_least_squares.cpp), Guarnera's pattern search (fit_pattern_search.cpp), mean
// or RMS CIEDE2000 (fit_de2000.cpp) — and the fit's summary.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "fit_problem.hpp"
#include "tristim/error.hpp"

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

namespace fit_detail {

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
  const int constant = constant_channel(rgb);
  if (pr.n > 1 && constant >= 0)
    throw Error(ErrorCode::IllConditioned, std::string("camera channel ") + "RGB"[constant] +
                                               " is constant over all " + std::to_string(pr.n) + " patches");
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

int constant_channel(const PatchMatrix& rgb, Eigen::Index skip) {
  for (int c = 0; c < 3; ++c) {
    double lo = INFINITY, hi = -INFINITY;
    for (Eigen::Index i = 0; i < rgb.rows(); ++i)
      if (i != skip) lo = std::min(lo, rgb(i, c)), hi = std::max(hi, rgb(i, c));
    const double mag = std::max(std::fabs(lo), std::fabs(hi));
    if (hi - lo <= 1e-12 * std::max(mag, 1e-300)) return c;
  }
  return -1;
}

namespace {

void add_message(FitResult& r, const std::string& m) {
  if (!r.message.empty()) r.message += "; ";
  r.message += m;
}

// An iterative objective's counts and losses into the result; at its limit, the status and `limit_message`.
void record_outcome(FitResult& r, const Outcome& o, const std::string& limit_message) {
  r.iterations = o.iterations;
  r.evaluations = o.evaluations;
  r.start_objective_value = o.f0;
  r.objective_value = o.f;
  if (o.hit_limit) {
    r.status = FitStatus::IterationLimit;
    add_message(r, limit_message);
  }
}

}  // namespace

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
    const Outcome o = pattern_search(pr, options.psm, z);
    record_outcome(r, o, "pattern search stopped at its iteration limit (" + std::to_string(o.iterations) + ")");
  } else if (options.objective == Objective::DeltaE2000) {
    const Outcome o = minimise_de2000(pr, options, z);
    record_outcome(r, o, "CIEDE2000 optimiser stopped at its limit (" + std::to_string(o.iterations) + " iterations, " +
                             std::to_string(o.evaluations) + " evaluations)");
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

}  // namespace fit_detail

FitResult fit(const std::string& model_id, const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
              const FitOptions& options) {
  if (model_id == kCorrected3x3) return fit_corrected_3x3(camera_RGB, reference_XYZ, options);  // not an objective's fit
  return fit_detail::fit_info(model_info(model_id), camera_RGB, reference_XYZ, options);
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

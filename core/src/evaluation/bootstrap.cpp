// Bootstrap confidence intervals of a fit (evaluation/bootstrap.hpp).
#include "tristim/evaluation/bootstrap.hpp"

#include <algorithm>
#include <cmath>

#include "../detmath.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"

namespace tristim {

namespace {

// splitmix64 (Steele, Lea & Flood 2014): integer arithmetic only, the same stream in every build.
struct Random {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }  // [0, 1)
  Eigen::Index below(Eigen::Index n) {  // [0, n), multiply-shift
    return static_cast<Eigen::Index>(((next() >> 32) * static_cast<uint64_t>(n)) >> 32);
  }
  double normal() {  // Marsaglia's polar method; detmath's log keeps native and wasm equal
    for (;;) {
      const double u = 2 * uniform() - 1, v = 2 * uniform() - 1, s = u * u + v * v;
      if (s > 0 && s < 1) return u * std::sqrt(-2 * detmath::log(s) / s);
    }
  }
};

double mean_dE00(const PatchMatrix& est, const PatchMatrix& ref, const Vec3& white) {
  double sum = 0;
  for (Eigen::Index i = 0; i < ref.rows(); ++i)
    sum += delta_E_CIE2000(XYZ_to_Lab(ref.row(i).transpose(), white), XYZ_to_Lab(est.row(i).transpose(), white));
  return sum / static_cast<double>(ref.rows());
}

void check(const PatchMatrix& rgb, const BootstrapOptions& b) {
  if (!(b.resamples >= 1 && b.resamples <= 100000))
    throw Error(ErrorCode::InvalidArgument, "bootstrap: resamples must be 1 to 100000, got " + std::to_string(b.resamples));
  if (!(b.level > 0 && b.level < 1))
    throw Error(ErrorCode::InvalidArgument, "bootstrap: level must lie in (0, 1)");
  const bool has_std = b.pixel_std.rows() > 0, has_n = !b.pixel_count.empty();
  if (has_std != has_n || (has_std && (b.pixel_std.rows() != rgb.rows() ||
                                       b.pixel_count.size() != static_cast<size_t>(rgb.rows()))))
    throw Error(ErrorCode::InvalidArgument, "bootstrap: pixel statistics need a std (3 channels) and a count per patch");
  for (Eigen::Index i = 0; i < b.pixel_std.rows(); ++i)
    if (!(b.pixel_std.row(i).minCoeff() >= 0) || !std::isfinite(b.pixel_std.row(i).maxCoeff()) || !(b.pixel_count[i] >= 1))
      throw Error(ErrorCode::InvalidArgument, "bootstrap: patch " + std::to_string(i + 1) +
                                                  ": pixel std must be finite and >= 0, the pixel count >= 1");
  if (!b.loo_dE00.empty() && b.loo_dE00.size() != static_cast<size_t>(rgb.rows()))
    throw Error(ErrorCode::InvalidArgument, "bootstrap: one leave-one-out error per patch");
}

}  // namespace

Interval percentile_interval(const std::vector<double>& values, double level) {
  Interval ci;
  ci.level = level;
  ci.lo = quantile(values, (1 - level) / 2);
  ci.hi = quantile(values, (1 + level) / 2);
  return ci;
}

BootstrapResult bootstrap_fit(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                              const FitOptions& options, const BootstrapOptions& b) {
  validate_patches(rgb, xyz);
  check(rgb, b);
  const FitResult full = fit(model_id, rgb, xyz, options);  // the data as given must fit (its errors are the caller's)
  const Eigen::Index n = rgb.rows(), p = full.model.coefficients.cols(), k = 3 * p;
  BootstrapResult out;
  out.level = b.level;
  out.seed = b.seed;
  out.pixels = b.pixel_std.rows() > 0;
  out.has_loo = !b.loo_dE00.empty();
  Eigen::MatrixXd coefficients(k, b.resamples);
  std::vector<double> train, loo;
  std::vector<Eigen::Vector3d> sum_x(static_cast<size_t>(n), Eigen::Vector3d::Zero());
  std::vector<Mat3> sum_xx(static_cast<size_t>(n), Mat3::Zero());
  Random random{b.seed};
  PatchMatrix r(n, 3), x(n, 3);
  std::vector<Eigen::Index> draw(static_cast<size_t>(n));
  FitOptions o = options;
  o.warn_condition = INFINITY;  // a resample's warnings are not reported
  const int step = std::max(1, b.resamples / 50);
  for (int s = 0; s < b.resamples; ++s) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index j = random.below(n);
      draw[static_cast<size_t>(i)] = j;
      r.row(i) = rgb.row(j);
      x.row(i) = xyz.row(j);
      if (out.pixels)
        for (int c = 0; c < 3; ++c) r(i, c) += b.pixel_std(j, c) / std::sqrt(b.pixel_count[static_cast<size_t>(j)]) * random.normal();
    }
    if (!options.weights.empty())
      for (Eigen::Index i = 0; i < n; ++i) o.weights[static_cast<size_t>(i)] = options.weights[static_cast<size_t>(draw[static_cast<size_t>(i)])];
    try {
      const FitResult f = fit(model_id, r, x, o);
      const int m = out.resamples++;
      for (int c = 0; c < 3; ++c)
        for (Eigen::Index t = 0; t < p; ++t) coefficients(c * p + t, m) = f.model.coefficients(c, t);
      train.push_back(mean_dE00(f.fitted, x, options.white));
      if (out.has_loo) {
        double sum = 0;
        for (Eigen::Index j : draw) sum += b.loo_dE00[static_cast<size_t>(j)];
        loo.push_back(sum / static_cast<double>(n));
      }
      const PatchMatrix predicted = predict(f.model, rgb);
      for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3d v = (predicted.row(i) - full.fitted.row(i)).transpose();  // shifted: no cancellation
        sum_x[static_cast<size_t>(i)] += v;
        sum_xx[static_cast<size_t>(i)] += v * v.transpose();
      }
    } catch (const Error&) {
      ++out.failed;
    }
    if (b.progress && ((s + 1) % step == 0 || s + 1 == b.resamples) && !b.progress(s + 1, b.resamples)) {
      out.cancelled = s + 1 < b.resamples;
      break;
    }
  }
  const int m = out.resamples;
  if (m < 2)
    throw Error(ErrorCode::NoUsableData, "bootstrap: " + std::to_string(m) + " of " + std::to_string(m + out.failed) +
                                             " resampled fits succeeded; no interval");
  coefficients.conservativeResize(k, m);
  out.train_dE00_mean = percentile_interval(train, b.level);
  if (out.has_loo) out.loo_dE00_mean = percentile_interval(loo, b.level);
  out.coefficients_lo.resize(3, p);
  out.coefficients_hi.resize(3, p);
  // Small-sample correction: the pairs bootstrap's spread is that of the heteroscedasticity-
  // consistent (sandwich) covariance HC0, which is low by N/(N − q) for q free coefficients per
  // channel (MacKinnon & White 1985, HC1). Deviations from the full fit are widened by
  // f = √(N/(N − q)), so 95 % intervals cover at 95 % for 24 patches (tests/bench/bench_bootstrap).
  const double q_free = static_cast<double>(p - (options.preserve_white && model_id != kCorrected3x3 ? 1 : 0));
  const double f = n > q_free ? std::sqrt(static_cast<double>(n) / (static_cast<double>(n) - q_free)) : 1.0;
  out.inflation = f;
  for (Eigen::Index q = 0; q < k; ++q) {
    std::vector<double> row(static_cast<size_t>(m));
    for (int s = 0; s < m; ++s) row[static_cast<size_t>(s)] = coefficients(q, s);
    const Interval ci = percentile_interval(row, b.level);
    const double centre = full.model.coefficients(q / p, q % p);
    out.coefficients_lo(q / p, q % p) = centre + f * (ci.lo - centre);
    out.coefficients_hi(q / p, q % p) = centre + f * (ci.hi - centre);
  }
  const Eigen::VectorXd mean = coefficients.rowwise().mean();
  const Eigen::MatrixXd centred = coefficients.colwise() - mean;
  out.covariance = f * f * centred * centred.transpose() / static_cast<double>(m - 1);
  out.predicted_XYZ_covariance.resize(static_cast<size_t>(n));
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    const Eigen::Vector3d mu = sum_x[i] / m;
    out.predicted_XYZ_covariance[i] = (sum_xx[i] - m * mu * mu.transpose()) / (m - 1);
  }
  return out;
}

json::Value interval_json(const Interval& interval) {
  json::Value o = json::Value::object();
  o.set("level", interval.level);
  o.set("lo", interval.lo);
  o.set("hi", interval.hi);
  return o;
}

json::Value bootstrap_json(const BootstrapResult& r, const Model& fitted) {
  json::Value o = json::Value::object();
  o.set("resamples", r.resamples);
  o.set("failed", r.failed);
  o.set("cancelled", r.cancelled);
  o.set("seed", static_cast<double>(r.seed));
  o.set("level", r.level);
  o.set("resampling", r.pixels ? "patches+pixels" : "patches");
  o.set("inflation", r.inflation);
  json::Value rows = json::Value::array();
  for (Eigen::Index c = 0; c < r.coefficients_lo.rows(); ++c) {
    json::Value row = json::Value::array();
    for (Eigen::Index t = 0; t < r.coefficients_lo.cols(); ++t) {
      json::Value k = json::Value::object();
      k.set("value", fitted.coefficients(c, t));
      k.set("ci", interval_json({r.level, r.coefficients_lo(c, t), r.coefficients_hi(c, t)}));
      row.push(k);
    }
    rows.push(row);
  }
  o.set("coefficients", rows);
  json::Value cov = json::Value::array();
  for (Eigen::Index i = 0; i < r.covariance.rows(); ++i) {
    std::vector<double> v(static_cast<size_t>(r.covariance.cols()));
    for (Eigen::Index j = 0; j < r.covariance.cols(); ++j) v[static_cast<size_t>(j)] = r.covariance(i, j);
    cov.push(json::Value(v));
  }
  o.set("covariance", cov);
  json::Value patches = json::Value::array();
  for (const Mat3& m : r.predicted_XYZ_covariance) {
    json::Value a = json::Value::array();
    for (int i = 0; i < 3; ++i) a.push(json::Value(std::vector<double>{m(i, 0), m(i, 1), m(i, 2)}));
    patches.push(a);
  }
  o.set("predicted_XYZ_covariance", patches);
  return o;
}

}  // namespace tristim

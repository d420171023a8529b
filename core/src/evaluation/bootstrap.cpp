// Bootstrap confidence intervals of a fit (evaluation/bootstrap.hpp).
#include "tristim/evaluation/bootstrap.hpp"

#include <algorithm>
#include <cmath>

#include "../detmath.hpp"
#include "tristim/error.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/profile/recipe.hpp"

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

Eigen::Vector2d xy_of(const Vec3& XYZ) { return XYZ_to_xy(XYZ); }
Eigen::Vector2d ab_of(const Vec3& XYZ, const Vec3& white) {
  const Vec3 Lab = XYZ_to_Lab(XYZ, white);
  return {Lab[1], Lab[2]};
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

BootstrapRun::BootstrapRun(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                           const FitOptions& options, const BootstrapOptions& b)
    : model_id_(model_id), rgb_(rgb), xyz_(xyz), options_(options), refit_options_(options), bootstrap_(b) {
  validate_patches(rgb, xyz);
  check(rgb, b);
  full_ = fit(model_id, rgb, xyz, options);  // the data as given must fit (its errors are the caller's)
  bootstrap_.progress = nullptr;
  refit_options_.warn_condition = INFINITY;  // a resample's warnings are not reported
  random_state_ = b.seed;
  const auto n = static_cast<size_t>(rgb.rows());
  coefficients_.resize(3 * full_.model.coefficients.cols(), b.resamples);
  sum_x_.assign(n, Eigen::Vector3d::Zero());
  sum_xx_.assign(n, Mat3::Zero());
  sum_xy_ab_.assign(n, Eigen::Vector4d::Zero());
  sum_xy_ab2_.assign(n, Eigen::Matrix4d::Zero());
  train_.reserve(static_cast<size_t>(b.resamples));  // no reallocation while stepping
  if (!b.loo_dE00.empty()) loo_.reserve(static_cast<size_t>(b.resamples));
  for (Eigen::Index i = 0; i < rgb.rows(); ++i) {
    full_xy_.push_back(xy_of(full_.fitted.row(i).transpose()));
    full_ab_.push_back(ab_of(full_.fitted.row(i).transpose(), options.white));
  }
}

int BootstrapRun::step(int count) {
  const Eigen::Index n = rgb_.rows(), p = full_.model.coefficients.cols();
  const bool pixels = bootstrap_.pixel_std.rows() > 0;
  Random random{random_state_};
  PatchMatrix r(n, 3), x(n, 3);
  std::vector<Eigen::Index> draw(static_cast<size_t>(n));
  for (; count > 0 && done_ < bootstrap_.resamples; --count, ++done_) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index j = random.below(n);
      draw[static_cast<size_t>(i)] = j;
      r.row(i) = rgb_.row(j);
      x.row(i) = xyz_.row(j);
      if (pixels)
        for (int c = 0; c < 3; ++c)
          r(i, c) += bootstrap_.pixel_std(j, c) / std::sqrt(bootstrap_.pixel_count[static_cast<size_t>(j)]) * random.normal();
    }
    if (!options_.weights.empty())
      for (Eigen::Index i = 0; i < n; ++i)
        refit_options_.weights[static_cast<size_t>(i)] = options_.weights[static_cast<size_t>(draw[static_cast<size_t>(i)])];
    try {
      const FitResult f = fit(model_id_, r, x, refit_options_);
      const int m = resamples_++;
      for (int c = 0; c < 3; ++c)
        for (Eigen::Index t = 0; t < p; ++t) coefficients_(c * p + t, m) = f.model.coefficients(c, t);
      train_.push_back(mean_dE00(f.fitted, x, options_.white));
      if (!bootstrap_.loo_dE00.empty()) {
        double sum = 0;
        for (Eigen::Index j : draw) sum += bootstrap_.loo_dE00[static_cast<size_t>(j)];
        loo_.push_back(sum / static_cast<double>(n));
      }
      const PatchMatrix predicted = predict(f.model, rgb_);
      for (Eigen::Index i = 0; i < n; ++i) {
        const auto k = static_cast<size_t>(i);
        const Vec3 XYZ = predicted.row(i).transpose();
        const Eigen::Vector3d v = XYZ - full_.fitted.row(i).transpose();  // shifted: no cancellation
        sum_x_[k] += v;
        sum_xx_[k] += v * v.transpose();
        Eigen::Vector4d w;
        w << xy_of(XYZ) - full_xy_[k], ab_of(XYZ, options_.white) - full_ab_[k];
        sum_xy_ab_[k] += w;
        sum_xy_ab2_[k] += w * w.transpose();
      }
    } catch (const Error&) {
      ++failed_;
    }
  }
  random_state_ = random.state;
  return done_;
}

BootstrapResult BootstrapRun::result() const {
  const Eigen::Index n = rgb_.rows(), p = full_.model.coefficients.cols(), k = 3 * p;
  const BootstrapOptions& b = bootstrap_;
  BootstrapResult out;
  out.level = b.level;
  out.seed = b.seed;
  out.pixels = b.pixel_std.rows() > 0;
  out.has_loo = !b.loo_dE00.empty();
  out.resamples = resamples_;
  out.failed = failed_;
  out.cancelled = done_ < b.resamples;
  const int m = resamples_;
  if (m < 2)
    throw Error(ErrorCode::NoUsableData, "bootstrap: " + std::to_string(m) + " of " + std::to_string(m + failed_) +
                                             " resampled fits succeeded; no interval");
  const Eigen::MatrixXd coefficients = coefficients_.leftCols(m);
  out.train_dE00_mean = percentile_interval(train_, b.level);
  if (out.has_loo) out.loo_dE00_mean = percentile_interval(loo_, b.level);
  out.coefficients_lo.resize(3, p);
  out.coefficients_hi.resize(3, p);
  // Small-sample correction: the pairs bootstrap's spread is that of the heteroscedasticity-
  // consistent (sandwich) covariance HC0, which is low by N/(N − q) for q free coefficients per
  // channel (MacKinnon & White 1985, HC1). Deviations from the full fit are widened by
  // f = √(N/(N − q)), so 95 % intervals cover at 95 % for 24 patches (tests/bench/bench_bootstrap).
  const double q_free = static_cast<double>(p - (options_.preserve_white && model_id_ != kCorrected3x3 ? 1 : 0));
  const double f = n > q_free ? std::sqrt(static_cast<double>(n) / (static_cast<double>(n) - q_free)) : 1.0;
  out.inflation = f;
  for (Eigen::Index q = 0; q < k; ++q) {
    std::vector<double> row(static_cast<size_t>(m));
    for (int s = 0; s < m; ++s) row[static_cast<size_t>(s)] = coefficients(q, s);
    const Interval ci = percentile_interval(row, b.level);
    const double centre = full_.model.coefficients(q / p, q % p);
    out.coefficients_lo(q / p, q % p) = centre + f * (ci.lo - centre);
    out.coefficients_hi(q / p, q % p) = centre + f * (ci.hi - centre);
  }
  const Eigen::VectorXd mean = coefficients.rowwise().mean();
  const Eigen::MatrixXd centred = coefficients.colwise() - mean;
  out.covariance = f * f * centred * centred.transpose() / static_cast<double>(m - 1);
  // The predictions' covariances take the same widening: for a model linear in its coefficients
  // (every least-squares model here) a patch's prediction is ŷ = J β with J = I₃ ⊗ φ(RGB)ᵀ, so the
  // refits' covariance of ŷ is exactly J Cov(β) Jᵀ and Cov(ŷ) = J (f² Cov(β)) Jᵀ = f² × it; xy and
  // a*b* are smooth functions of ŷ, widened by f² to first order (the delta method). The ellipses
  // then cover the truth at `level` (tests/core/evaluation/bootstrap_test.cpp).
  const double f2 = f * f;
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    const Eigen::Vector3d mu = sum_x_[i] / m;
    out.predicted_XYZ_covariance.push_back(f2 * (sum_xx_[i] - m * mu * mu.transpose()) / (m - 1));
    const Eigen::Vector4d nu = sum_xy_ab_[i] / m;
    const Eigen::Matrix4d c = f2 * (sum_xy_ab2_[i] - m * nu * nu.transpose()) / (m - 1);
    out.predicted_xy_covariance.push_back(c.topLeftCorner<2, 2>());
    out.predicted_ab_covariance.push_back(c.bottomRightCorner<2, 2>());
  }
  // The ellipse's radius k (x'Σ⁻¹x = k²): Σ is estimated from the same N patches, so x'Σ⁻¹x/2 is
  // Hotelling's F(2, ν) with ν = N − q residual degrees of freedom (not χ²₂/2, which holds for a known
  // Σ and left 95 % ellipses covering the truth 92 % of the time on 24 patches). F(2, ν)'s quantile
  // is closed-form, P(F > t) = (1 + 2t/ν)^(−ν/2), so k² = ν((1 − level)^(−2/ν) − 1), which tends to
  // −2 ln(1 − level) (χ²₂) as ν → ∞; too few patches (ν ≤ 0): the χ²₂ radius.
  const double nu = static_cast<double>(n) - q_free;
  out.ellipse_scale = nu > 0 ? std::sqrt(nu * (detmath::exp(-2 / nu * detmath::log(1 - b.level)) - 1))
                             : std::sqrt(-2 * detmath::log(1 - b.level));
  return out;
}

BootstrapResult bootstrap_fit(const std::string& model_id, const PatchMatrix& rgb, const PatchMatrix& xyz,
                              const FitOptions& options, const BootstrapOptions& b) {
  BootstrapRun run(model_id, rgb, xyz, options, b);
  const int step = std::max(1, b.resamples / 50);
  while (run.done() < run.total()) {
    const int done = run.step(1);
    if (b.progress && (done % step == 0 || done == run.total()) && !b.progress(done, run.total())) break;
  }
  return run.result();
}

MethodInfo bootstrap_option_table() {
  return {
      "bootstrap", "Uncertainty (bootstrap)",
      "Efron's pairs bootstrap over the patches and, where each patch's pixel spread is known, over its pixels "
      "(percentile intervals; coefficients and predicted colours widened by the HC1 factor, MacKinnon & White 1985)",
      {{"resamples", "integer", "Resamples", 1000, "", 1, 100000, {}, "number of refits on patches drawn with replacement"},
       {"seed", "integer", "Seed", 1, "", 0, 9007199254740992.0, {}, "the random stream's seed: the same seed gives the same intervals"},
       {"level", "number", "Level", 0.95, "", 0, 1, {}, "confidence level of the intervals and ellipses, strictly between 0 and 1"}}};
}

BootstrapRun bootstrap_recipe(const Recipe& recipe, const std::vector<std::string>& ids, const PatchMatrix& rgb,
                              const PatchMatrix& xyz, const std::vector<double>& loo_dE00, const MethodChoice& settings,
                              const PatchMatrix& pixel_std, const std::vector<double>& pixel_count) {
  if (ids.size() != static_cast<size_t>(rgb.rows()))
    throw Error(ErrorCode::InvalidArgument, "bootstrap: " + std::to_string(ids.size()) + " patch ids for " +
                                                std::to_string(rgb.rows()) + " patches");
  MethodChoice s = settings;
  const MethodInfo table = bootstrap_option_table();
  if (s.method.empty()) s.method = table.id;
  s = complete_choice(table, s);
  BootstrapOptions b;
  b.resamples = static_cast<int>(choice_number(s, "resamples"));
  b.seed = static_cast<uint64_t>(choice_number(s, "seed"));
  b.level = choice_number(s, "level");
  b.loo_dE00 = loo_dE00;
  const Recipe complete = complete_recipe(recipe);
  if (complete.linearisation.method == "identity") {  // checked as any BootstrapOptions' (check())
    b.pixel_std = pixel_std;
    b.pixel_count = pixel_count;
  }
  int white_index = -1;
  const FitOptions options = recipe_fit_options(recipe, ids, rgb, xyz, white_index);
  return BootstrapRun(complete.characterisation.model, rgb, xyz, options, b);
}

std::string profile_with_bootstrap(const std::string& profile_json, const BootstrapRun& run) {
  json::Value p = json::parse(profile_json);
  add_bootstrap_to_profile(p, run.result(), run.model());
  return p.dump(2) + "\n";
}

json::Value summary_with_ci(const json::Value& summary, const Interval& ci) {
  json::Value out = json::Value::object();
  for (const auto& m : summary.members()) {
    if (m.first == "ci") continue;  // a previous run's
    out.set(m.first, m.second);
    if (m.first == "mean") out.set("ci", interval_json(ci));
  }
  return out;
}

void add_bootstrap_to_profile(json::Value& p, const BootstrapResult& r, const Model& fitted) {
  if (const json::Value* found = p.find("metrics")) {
    json::Value metrics = *found;
    const auto put = [&](const char* set, const Interval& ci) {
      const json::Value* m0 = metrics.find(set);
      if (!m0 || !m0->find("dE00")) return;
      json::Value m = *m0;
      m.set("dE00", summary_with_ci(*m.find("dE00"), ci));
      metrics.set(set, m);
    };
    put("training", r.train_dE00_mean);
    if (r.has_loo) put("loo", r.loo_dE00_mean);
    p.set("metrics", metrics);
  }
  p.set("bootstrap", bootstrap_json(r, fitted));
}

json::Value interval_json(const Interval& interval) {
  return fields::object({{"level", interval.level}, {"lo", interval.lo}, {"hi", interval.hi}});
}

json::Value bootstrap_json(const BootstrapResult& r, const Model& fitted) {
  json::Value o = fields::object({{"resamples", r.resamples}, {"failed", r.failed}, {"cancelled", r.cancelled},
                                  {"seed", static_cast<double>(r.seed)}, {"level", r.level},
                                  {"resampling", r.pixels ? "patches+pixels" : "patches"}, {"inflation", r.inflation}});
  json::Value rows = json::Value::array();
  for (Eigen::Index c = 0; c < r.coefficients_lo.rows(); ++c) {
    json::Value row = json::Value::array();
    for (Eigen::Index t = 0; t < r.coefficients_lo.cols(); ++t) {
      row.push(fields::object({{"value", fitted.coefficients(c, t)},
                               {"ci", interval_json({r.level, r.coefficients_lo(c, t), r.coefficients_hi(c, t)})}}));
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
  for (const auto& [name, list] : {std::pair{"predicted_xy_covariance", &r.predicted_xy_covariance},
                                   std::pair{"predicted_ab_covariance", &r.predicted_ab_covariance}}) {
    json::Value a = json::Value::array();
    for (const Eigen::Matrix2d& m : *list) {
      json::Value rows2 = json::Value::array();
      for (int i = 0; i < 2; ++i) rows2.push(json::Value(std::vector<double>{m(i, 0), m(i, 1)}));
      a.push(rows2);
    }
    o.set(name, a);
  }
  o.set("ellipse_scale", r.ellipse_scale);
  return o;
}

}  // namespace tristim

// Simulated charts for the bootstrap's coverage checks (tests/core/evaluation/bootstrap_test.cpp
// and tests/bench/bench_bootstrap.cpp): 24 patches, RGB uniform in [5, 95], XYZ = M·RGB plus
// Gaussian noise, from a stream independent of the bootstrap's own.
// Also: the ellipses' coverage of the predicted truth (ellipse_coverage_3x3).
#pragma once
#include <cmath>
#include <cstdint>
#include <utility>

#include <Eigen/LU>

#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/evaluation/bootstrap.hpp"

namespace tristim::test {

struct Simulation {
  uint64_t s;
  double u() {  // splitmix64 -> [0, 1)
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  }
  double normal() { return std::sqrt(-2 * std::log(1 - u())) * std::cos(6.283185307179586 * u()); }  // Box-Muller
};

inline Mat3 planted_matrix() {
  Mat3 M;
  M << 0.62, 0.21, 0.13, 0.28, 0.68, 0.06, 0.02, 0.11, 0.85;
  return M;
}

/// One simulated chart of `n` patches with noise σ on each XYZ channel.
inline void simulate_chart(Simulation& sim, PatchMatrix& rgb, PatchMatrix& xyz, double sigma, int n = 24) {
  const Mat3 M = planted_matrix();
  rgb.resize(n, 3);
  xyz.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) rgb(i, c) = 5 + 90 * sim.u();
    const Vec3 v = M * rgb.row(i).transpose();
    for (int c = 0; c < 3; ++c) xyz(i, c) = v[c] + sigma * sim.normal();
  }
}


/// A chart simulated (simulate_chart, 24 patches) from the stream `seed`.
struct SimulatedChart {
  PatchMatrix rgb, xyz;
};
inline SimulatedChart simulated_chart(uint64_t seed, double sigma) {
  Simulation sim{seed};
  SimulatedChart c;
  simulate_chart(sim, c.rgb, c.xyz, sigma);
  return c;
}

/// Bootstrap options with `resamples` resamples at `level` (the other options' defaults).
inline BootstrapOptions resampling(int resamples, double level = 0.95) {
  BootstrapOptions b;
  b.resamples = resamples;
  b.level = level;
  return b;
}

/// Runs `each(rgb, run, result)` on `charts` simulated charts (σ = 1, 24 patches), each with a
/// `resamples`-resample bootstrap of a matrix-3x3 least-squares fit at `level` (seeds 1, 2, …).
template <class F>
void simulated_bootstraps(Simulation& sim, int charts, int resamples, double level, F&& each) {
  PatchMatrix rgb, xyz;
  for (int run = 0; run < charts; ++run) {
    simulate_chart(sim, rgb, xyz, 1.0);
    BootstrapOptions b = resampling(resamples, level);
    b.seed = static_cast<uint64_t>(run + 1);
    BootstrapRun boot("matrix-3x3", rgb, xyz, FitOptions{}, b);
    boot.step(resamples);
    each(rgb, boot, boot.result());
  }
}

/// Coverage over `charts` simulated charts of the planted matrix by the 9 coefficient intervals
/// (95 %) of `resamples`-resample bootstraps (simulated_bootstraps): {covered, total}.
inline std::pair<long, long> coverage_3x3(Simulation& sim, int charts, int resamples) {
  const Mat3 M = planted_matrix();
  long covered = 0, total = 0;
  simulated_bootstraps(sim, charts, resamples, 0.95, [&](const PatchMatrix&, const BootstrapRun&, const BootstrapResult& r) {
    for (int c = 0; c < 3; ++c)
      for (int t = 0; t < 3; ++t, ++total) covered += r.coefficients_lo(c, t) <= M(c, t) && M(c, t) <= r.coefficients_hi(c, t);
  });
  return {covered, total};
}

/// How often the `level` ellipses of the predictions (predicted_xy_covariance and
/// predicted_ab_covariance with ellipse_scale, centred on the full fit's prediction) hold the
/// truth (xy and a*b* of the planted M·RGB), over `charts` simulated charts × 24 patches
/// (simulated_bootstraps).
struct EllipseCoverage {
  long xy = 0, ab = 0, total = 0;
};
inline EllipseCoverage ellipse_coverage_3x3(Simulation& sim, int charts, int resamples, double level = 0.95) {
  const Mat3 M = planted_matrix();
  const Vec3 white = FitOptions{}.white;
  const auto inside = [](const Eigen::Vector2d& d, const Eigen::Matrix2d& cov, double k) {
    return d.dot(cov.inverse() * d) <= k * k;  // x'Σ⁻¹x ≤ k²
  };
  EllipseCoverage out;
  simulated_bootstraps(sim, charts, resamples, level, [&](const PatchMatrix& rgb, const BootstrapRun& boot, const BootstrapResult& r) {
    const PatchMatrix centre = predict(boot.model(), rgb);
    for (Eigen::Index i = 0; i < rgb.rows(); ++i, ++out.total) {
      const Vec3 truth = M * rgb.row(i).transpose(), fitted = centre.row(i).transpose();
      const auto k = static_cast<size_t>(i);
      out.xy += inside(XYZ_to_xy(truth) - XYZ_to_xy(fitted), r.predicted_xy_covariance[k], r.ellipse_scale);
      const Vec3 a = XYZ_to_Lab(truth, white), e = XYZ_to_Lab(fitted, white);
      out.ab += inside(Eigen::Vector2d(a[1] - e[1], a[2] - e[2]), r.predicted_ab_covariance[k], r.ellipse_scale);
    }
  });
  return out;
}

}  // namespace tristim::test

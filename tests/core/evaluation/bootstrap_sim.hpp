// Simulated charts for the bootstrap's coverage checks (tests/core/evaluation/bootstrap_test.cpp
// and tests/bench/bench_bootstrap.cpp): 24 patches, RGB uniform in [5, 95], XYZ = M·RGB plus
// Gaussian noise, from a stream independent of the bootstrap's own.
#pragma once
#include <cmath>
#include <cstdint>
#include <utility>

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

/// Coverage over `charts` simulated charts (σ = 1) of the planted matrix by the 9 coefficient
/// intervals of a `resamples`-resample bootstrap of a matrix-3x3 least-squares fit (seeds 1, 2, …):
/// {covered, total}.
inline std::pair<long, long> coverage_3x3(Simulation& sim, int charts, int resamples) {
  const Mat3 M = planted_matrix();
  long covered = 0, total = 0;
  PatchMatrix rgb, xyz;
  for (int run = 0; run < charts; ++run) {
    simulate_chart(sim, rgb, xyz, 1.0);
    BootstrapOptions b;
    b.resamples = resamples;
    b.seed = static_cast<uint64_t>(run + 1);
    const BootstrapResult r = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b);
    for (int c = 0; c < 3; ++c)
      for (int t = 0; t < 3; ++t, ++total) covered += r.coefficients_lo(c, t) <= M(c, t) && M(c, t) <= r.coefficients_hi(c, t);
  }
  return {covered, total};
}

}  // namespace tristim::test

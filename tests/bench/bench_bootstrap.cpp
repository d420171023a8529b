// Output lines "BENCH <case> <step> <ms>" and "CASE <case> <text>" are read by scripts/bench.sh
// (native and wasm side by side); the other lines are for a human running it directly.
// Benchmark: bootstrap confidence intervals (evaluation/bootstrap.hpp). 1,000 resamples of a
// 24-patch 3×3 least-squares fit (issue 47's target: < 50 ms natively, within 1.5× in wasm), and
// the full coverage check: 95 % intervals on 1,000 simulated charts × 1,000 resamples should cover
// the planted coefficients in 93–97 % of cases (the test asserts a smaller version). Prints
// figures; asserts nothing.
#include <cmath>
#include <cstdio>

#include "../core/evaluation/bootstrap_sim.hpp"
#include "bench_util.hpp"
#include "tristim/evaluation/bootstrap.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/evaluation/evaluation.hpp"

using namespace tristim;
using namespace tristim::bench;

int main() {
  const char* where = build_name();
  std::printf("bench_bootstrap (%s)\n", where);
  test::Simulation sim{2026};
  PatchMatrix rgb, xyz;
  test::simulate_chart(sim, rgb, xyz, 1.0);
  BootstrapOptions b;
  b.resamples = 1000;
  b.loo_dE00 = evaluate_model("matrix-3x3", rgb, xyz).loo.patches.dE00;
  BootstrapResult r;
  const double first = time_ms([&] { r = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b); });
  std::printf("BENCH bootstrap-3x3-24 first-call %.3f\n", first);
  const double ms = best_ms(5, [&] { r = bootstrap_fit("matrix-3x3", rgb, xyz, FitOptions{}, b); });
  std::printf("\n== 1000 resamples of a 24-patch matrix-3x3 ls fit (with leave-one-out interval), best of 5 ==\n");
  std::printf("BENCH bootstrap-3x3-24 resamples-1000 %.3f\n", ms);
  std::printf("  %.3f ms; training mean dE00 95%% CI [%.3f, %.3f], leave-one-out [%.3f, %.3f]\n", ms,
              r.train_dE00_mean.lo, r.train_dE00_mean.hi, r.loo_dE00_mean.lo, r.loo_dE00_mean.hi);
  // Where a resample's time goes: the refit, the training CIEDE2000 of 24 patches, and the 24
  // predictions with their xy and a*b* (each 1,000 times, as in 1,000 resamples).
  FitOptions quiet;
  quiet.warn_condition = INFINITY;
  const FitResult full = fit("matrix-3x3", rgb, xyz, quiet);
  double sink = 0;
  std::printf("BENCH bootstrap-parts fit-x1000 %.3f\n", best_ms(5, [&] {
                for (int i = 0; i < 1000; ++i) sink += fit("matrix-3x3", rgb, xyz, quiet).model.coefficients(0, 0);
              }));
  std::printf("BENCH bootstrap-parts dE00-24x1000 %.3f\n", best_ms(5, [&] {
                for (int i = 0; i < 1000; ++i)
                  for (Eigen::Index k = 0; k < xyz.rows(); ++k)
                    sink += delta_E_CIE2000(XYZ_to_Lab(xyz.row(k).transpose(), quiet.white),
                                            XYZ_to_Lab(full.fitted.row(k).transpose(), quiet.white));
              }));
  std::printf("BENCH bootstrap-parts predict-xy-ab-24x1000 %.3f\n", best_ms(5, [&] {
                for (int i = 0; i < 1000; ++i) {
                  const PatchMatrix p = predict(full.model, rgb);
                  for (Eigen::Index k = 0; k < p.rows(); ++k)
                    sink += XYZ_to_xy(p.row(k).transpose())[0] + XYZ_to_Lab(p.row(k).transpose(), quiet.white)[1];
                }
              }));
  std::printf("  (checksum %g)\n", sink);
  for (const char* model : {"matrix-3x4", "Finlayson2015-2", "Cheung2004-10"}) {
    const double t = best_ms(3, [&] { r = bootstrap_fit(model, rgb, xyz, FitOptions{}, b); });
    std::printf("BENCH bootstrap-%s-24 resamples-1000 %.3f\n", model, t);
  }

  std::printf("\n== coverage: 1000 simulated charts x 1000 resamples, 95 %% intervals, 9 coefficients ==\n");
  const auto t0 = Clock::now();
  const auto [covered, total] = test::coverage_3x3(sim, 1000, 1000);
  std::printf("CASE coverage %.4f of %ld intervals (target 0.93-0.97) in %.1f s\n", static_cast<double>(covered) / total,
              total, ms_since(t0) / 1000);
  return 0;
}

// Output lines "BENCH <case> <step> <ms>" and "CASE <case> <text>" are read by scripts/bench.sh
// (native and wasm side by side); the other lines are for a human running it directly.
// Benchmark: model fits (LS of every model on 140 patches, pattern search, CIEDE2000 objective)
// and applying a degree-2 root-polynomial to a 24 MP float RGB image next to a plain memcpy of
// the same size. Prints figures; asserts nothing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bench_util.hpp"
#include "test_files.hpp"
#include "simd4.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"

using namespace tristim;
using namespace tristim::bench;

namespace {

// 140 synthetic patches (an SG-sized chart): camera RGB in raw counts, XYZ (Y = 100 white)
// from a plausible root-polynomial camera plus ~0.5 % noise. The same doubles in both builds:
// the standard distributions are not portable (libstdc++ natively and libc++ in wasm drew other
// patches from the same seed, so the native and wasm rows fitted different data, with different
// iteration counts), so only mt19937's integers (specified exactly) and IEEE arithmetic are used:
// uniform u = (k + 0.5) / 2^32, noise = 0.005 x (sum of 12 uniforms - 6) (Irwin-Hall, sd 1).
void make_patches(int n, PatchMatrix& rgb, PatchMatrix& xyz) {
  std::mt19937 rng(140);
  auto uniform = [&] { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; };
  auto noise = [&] {
    double s = 0;
    for (int k = 0; k < 12; ++k) s += uniform();
    return 0.005 * (s - 6.0);
  };
  Model truth{"Finlayson2015-2", Eigen::MatrixXd(3, 6)};
  truth.coefficients << 0.010, 0.0075, 0.0037, 0.002, 0.0012, 0.001, 0.005, 0.0175, 0.002, 0.001, 0.002, 0.0012,
      0.0005, 0.0025, 0.0225, 0.0005, 0.001, 0.002;
  rgb.resize(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb(i, c) = (0.02 + 0.93 * uniform()) * 4000.0;
  xyz = predict(truth, rgb);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) xyz(i, c) = std::max(0.0, xyz(i, c) * (1 + noise()));
}

// The Passport DNG's 24 patches (camera RGB derived by dcraw_emu) and the X-Rite after-Nov-2014
// L*a*b* D50 reference, as examples/compare/compare_passport.py uses them. A missing or short file
// ends the benchmark with an error naming it.
void read_passport(PatchMatrix& rgb, PatchMatrix& xyz) {
  auto rows = [](const std::string& file) {
    const std::string path = tristim::test::test_file_path(TRISTIM_SOURCE_DIR, file);
    std::ifstream in(path);
    if (!in) {
      std::printf("ERROR bench_models: '%s' not found\n", path.c_str());
      std::exit(1);
    }
    std::vector<std::vector<std::string>> out;
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string cell;
      std::vector<std::string> cells;
      while (std::getline(ls, cell, ',')) cells.push_back(cell);
      if (cells.size() >= 5) out.push_back(cells);
    }
    return out;
  };
  const auto r = rows(tristim::test::passport_rgb_csv);
  const auto l = rows("core/data/charts/colorchecker24_xrite_after_nov2014_Lab_D50.csv");
  if (r.size() != 24 || l.size() != 24) {
    std::printf("ERROR bench_models: the Passport tables do not have 24 rows\n");
    std::exit(1);
  }
  rgb.resize(24, 3);
  xyz.resize(24, 3);
  for (int i = 0; i < 24; ++i) {
    for (int c = 0; c < 3; ++c) rgb(i, c) = std::stod(r[i][2 + c]);
    const Vec3 Lab(std::stod(l[i][2]), std::stod(l[i][3]), std::stod(l[i][4]));
    xyz.row(i) = Lab_to_XYZ(Lab, whites::D50()).transpose();
  }
}

// The CIEDE2000 objective with the RMS loss, minimised by `algorithm` ("auto": Levenberg-Marquardt).
FitOptions rms_de2000(const char* algorithm) {
  FitOptions o;
  o.objective = Objective::DeltaE2000;
  o.de2000.rms = true;
  o.de2000.algorithm = algorithm;
  return o;
}

}  // namespace

int main() {
  const char* where = build_name();
  std::printf("bench_models (%s)\n", where);
  PatchMatrix rgb, xyz;
  make_patches(140, rgb, xyz);
  // Both builds must print the same sums (the same patches), or their rows are not comparable.
  double sum_rgb = 0, sum_xyz = 0;  // in order (Eigen's sum() is ordered differently with SIMD)
  for (int i = 0; i < 140; ++i)
    for (int c = 0; c < 3; ++c) sum_rgb += rgb(i, c), sum_xyz += xyz(i, c);
  std::printf("synthetic patches: sum RGB %.17g, sum XYZ %.17g\n", sum_rgb, sum_xyz);

  // Each model is fitted for ~30 ms before the timed fits: a fit takes microseconds, and V8 runs a
  // wasm function in its baseline tier (Liftoff) until it is hot and its optimised code arrives
  // from a background compile, so 20 cold fits timed mostly the baseline tier (1.4–1.8× slower
  // than the optimised code). The warm-up brings the rows closer to steady state but
  // not reliably all the way (tier-up arrives from a background compile; default node has
  // been seen at ~2× the figures of `node --no-liftoff`, which runs the optimised code alone). The
  // first fit of the process is printed for a human.
  std::printf("\n== least-squares fit, 140 patches (best of 20 after ~30 ms of warm-up) ==\n");
  for (const ModelInfo& m : model_table()) {
    if (!m.duplicate_of.empty()) continue;
    FitOptions o;
    const double first = time_ms([&] { (void)fit(m.id, rgb, xyz, o); });
    for (double spent = first; spent < 30;) spent += time_ms([&] { (void)fit(m.id, rgb, xyz, o); });
    const double t = best_ms(20, [&] { (void)fit(m.id, rgb, xyz, o); });
    std::printf("  %-18s %2d terms  %8.3f ms  (first fit %.3f ms)\n", m.id.c_str(), m.n_terms, t, first);
    std::printf("BENCH ls_140 %s %.4f\n", m.id.c_str(), t);
  }

  std::printf("\n== pattern search (Guarnera 2018 Algorithm 2), 140 patches (best of 5) ==\n");
  for (const char* id : {"Guarnera2018-T1", "Guarnera2018-To", "Guarnera2018-T2R"}) {
    FitOptions o;
    o.objective = Objective::PatternSearch;
    FitResult r;
    const double t = best_ms(5, [&] { r = fit(id, rgb, xyz, o); });
    std::printf("  %-18s %8.3f ms  %5d iterations  %6d evaluations  cost %.4g -> %.4g\n", id, t, r.iterations,
                r.evaluations, r.start_objective_value, r.objective_value);
    std::printf("BENCH psm_140 %s %.3f\n", id, t);
  }

  std::printf("\n== CIEDE2000 objective, mean loss (algorithm auto: iteratively reweighted LM), best of 5 ==\n");
  for (int n : {24, 140})
    for (const char* id : {"matrix-3x3", "matrix-3x4", "Finlayson2015-2"}) {
      FitOptions o;
      o.objective = Objective::DeltaE2000;
      FitResult r;
      const PatchMatrix a = rgb.topRows(n), b = xyz.topRows(n);
      const double t = best_ms(5, [&] { r = fit(id, a, b, o); });
      std::printf("  %3d patches %-16s %8.3f ms  %5d evaluations  mean dE00 %.4f -> %.4f\n", n, id, t,
                  r.evaluations, r.start_objective_value, r.objective_value);
      std::printf("BENCH de2000_%d %s %.3f\n", n, id, t);
    }

  std::printf("\n== CIEDE2000 objective, RMS loss: Levenberg-Marquardt (auto) vs NLopt BOBYQA, best of 5 ==\n");
  for (int n : {24, 140})
    for (const char* id : {"matrix-3x3", "matrix-3x4", "Finlayson2015-2"})
      for (const char* alg : {"auto", "bobyqa"}) {
        const FitOptions o = rms_de2000(alg);
        FitResult r;
        const PatchMatrix a = rgb.topRows(n), b = xyz.topRows(n);
        const double t = best_ms(5, [&] { r = fit(id, a, b, o); });
        std::printf("  %3d patches %-16s %-6s %8.3f ms  %4d iterations %5d evaluations  RMS dE00 %.4f -> %.10f\n",
                    n, id, alg, t, r.iterations, r.evaluations, r.start_objective_value, r.objective_value);
        std::printf("BENCH de2000_rms_%s_%d %s %.3f\n", alg, n, id, t);
      }

  {
    PatchMatrix prgb, pxyz;
    std::printf("\n== Passport DNG patches, matrix-3x3, RMS CIEDE2000 (OpenCV ccm: 3.331), best of 20 ==\n");
    read_passport(prgb, pxyz);
    for (const char* alg : {"auto", "bobyqa"}) {
        const FitOptions o = rms_de2000(alg);
        FitResult r;
        const double t = best_ms(20, [&] { r = fit("matrix-3x3", prgb, pxyz, o); });
        const auto& m = r.model.coefficients;
        std::printf("  %-6s %8.3f ms  %4d iterations %5d evaluations  RMS %.4f -> %.12f  M row 1 %.12g %.12g %.12g\n",
                    alg, t, r.iterations, r.evaluations, r.start_objective_value, r.objective_value, m(0, 0), m(0, 1),
                    m(0, 2));
        std::printf("BENCH de2000_rms_passport matrix-3x3_%s %.3f\n", alg, t);
      }
  }

  {
    // Issue 13: `tristim compare` on the Passport patches, every model x objective with
    // leave-one-out (51 rows; natively the rows are spread over the hardware threads).
    PatchMatrix prgb, pxyz;
    std::printf("\n== compare: Passport patches, every model x objective with leave-one-out (best of 3) ==\n");
    read_passport(prgb, pxyz);
    {
      // One thread in both builds, so the ratio compares like with like: natively compare_models
      // spreads its rows over the hardware threads (the rows "<objective>_threads", native only, as
      // the CLI runs), while the wasm build runs them in order (the page spreads them over workers:
      // tests/web/bench_journey.mjs).
      auto objectives = [](const std::string& objs) {
        return objs == "all" ? std::vector<Objective>{Objective::LeastSquares, Objective::PatternSearch,
                                                      Objective::DeltaE2000}
                             : std::vector<Objective>{objective_from_id(objs)};
      };
      set_compare_threads(1);
      for (const char* objs : {"ls", "psm", "de2000", "all"}) {
        std::size_t n_rows = 0;
        const double t = best_ms(3, [&] { n_rows = compare_models(prgb, pxyz, FitOptions{}, {}, objectives(objs)).size(); });
        std::printf("  %-7s %3zu rows, one thread %10.1f ms\n", objs, n_rows, t);
        std::printf("BENCH compare_passport %s %.1f\n", objs, t);
      }
      set_compare_threads(0);
#ifndef __EMSCRIPTEN__
      for (const char* objs : {"psm", "de2000", "all"}) {
        const double t = best_ms(3, [&] { (void)compare_models(prgb, pxyz, FitOptions{}, {}, objectives(objs)); });
        std::printf("  %-7s %u threads %10.1f ms\n", objs, std::max(1u, std::thread::hardware_concurrency()), t);
        std::printf("BENCH compare_passport %s_threads %.1f\n", objs, t);
      }
#endif
      std::printf("CASE compare_passport tristim compare on 24 Passport patches, every model x objective with "
                  "leave-one-out\n");
    }
  }

  std::printf("\n== leave-one-out, 140 patches, ls (best of 3) ==\n");
  for (const char* id : {"matrix-3x3", "Finlayson2015-2", "Cheung2004-20"}) {
    const double t = best_ms(3, [&] { (void)leave_one_out(id, rgb, xyz); });
    std::printf("  %-18s %8.3f ms\n", id, t);
    std::printf("BENCH loo_140 %s %.3f\n", id, t);
  }

  std::printf("\n== apply Finlayson2015-2 to a 24 MP float RGB image vs memcpy ==\n");
  const size_t w = 6000, h = 4000, n = w * h;
  const size_t bytes = n * 3 * sizeof(float);
  std::vector<float> in(n * 3), out(n * 3);
  for (size_t i = 0; i < n * 3; ++i) in[i] = static_cast<float>((i * 2654435761u) % 16384);
  std::memset(out.data(), 0, bytes);
  Model m = fit("Finlayson2015-2", rgb, xyz).model;
  const double t_copy = best_ms(5, [&] { std::memcpy(out.data(), in.data(), bytes); });
  volatile float sink = out[n];
  const double t_apply = best_ms(5, [&] { apply_to_image(m, in.data(), n, out.data()); });
  sink = out[n * 3 - 1];
  (void)sink;
  const double mb = bytes / 1048576.0;
  std::printf("  image %zux%zu, %.1f MB in, %.1f MB out\n", w, h, mb, mb);
  std::printf("  memcpy            %8.2f ms  (%.2f GB/s)\n", t_copy, bytes / t_copy / 1e6);
  std::printf("  apply root-poly 2 %8.2f ms  (%.2f GB/s read)  = %.0f %% of memcpy speed\n", t_apply,
              bytes / t_apply / 1e6, 100.0 * t_copy / t_apply);
  Model lin = fit("matrix-3x3", rgb, xyz).model;
  const double t_lin = best_ms(5, [&] { apply_to_image(lin, in.data(), n, out.data()); });
  std::printf("  apply 3x3 matrix  %8.2f ms  = %.0f %% of memcpy speed\n", t_lin, 100.0 * t_copy / t_lin);
  std::printf("CASE apply_24MP %zux%zu float RGB -> XYZ (%.0f MB each way): root-poly 2 at %.0f %%, 3x3 at %.0f %% "
              "of memcpy speed (%s)\n", w, h, mb, 100.0 * t_copy / t_apply, 100.0 * t_copy / t_lin, where);
  std::printf("BENCH apply_24MP memcpy %.2f\n", t_copy);
  std::printf("BENCH apply_24MP root-poly-2 %.2f\n", t_apply);
  std::printf("BENCH apply_24MP matrix-3x3 %.2f\n", t_lin);
  // In place (xyz == rgb), as apply_profile runs when the profile has a linearisation stage: each
  // line is read before it is written anyway, so plain stores cost no extra read and wasm loses
  // less to the native streaming stores. The image is refreshed (untimed) before each call.
  const auto best_in_place = [&](const Model& model) {
    double best = 1e300;
    for (int r = 0; r < 5; ++r) {
      std::memcpy(out.data(), in.data(), bytes);
      best = std::min(best, time_ms([&] { apply_to_image(model, out.data(), n, out.data()); }));
    }
    return best;
  };
  const double t_apply_ip = best_in_place(m), t_lin_ip = best_in_place(lin);
  std::printf("  in place: root-poly 2 %8.2f ms, 3x3 %8.2f ms\n", t_apply_ip, t_lin_ip);
  std::printf("BENCH apply_24MP root-poly-2-in-place %.2f\n", t_apply_ip);
  std::printf("BENCH apply_24MP matrix-3x3-in-place %.2f\n", t_lin_ip);
#ifdef TRISTIM_SIMD4
  // The floor of any kernel that writes with plain stores, as wasm must (it has no non-temporal
  // store): the same bytes copied 16 bytes at a time, no arithmetic. Each output line is read
  // before it is written (write-allocate), so this moves 1.5x memcpy's bytes in both builds. The
  // + 0.0f keeps clang from turning the loop into memory.copy (V8 runs that as memmove).
  const double t_floor = best_ms(5, [&] {
    const float* src = in.data();
    float* dst = out.data();
    const simd4::f4 zero = simd4::splat(0.f);
    for (size_t i = 0; i + 4 <= n * 3; i += 4) simd4::store(dst + i, simd4::add(simd4::load(src + i), zero));
  });
  std::printf("  plain-store copy  %8.2f ms  = %.0f %% of memcpy speed (the floor for plain stores)\n", t_floor,
              100.0 * t_copy / t_floor);
  std::printf("BENCH apply_24MP plain-store-copy %.2f\n", t_floor);
#endif
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
  // The narrower native kernels on the same image (the default above is the widest the CPU has):
  // AVX2+FMA, and the 4-lane SSE2 kernel that does the wasm SIMD128 kernel's arithmetic.
  for (int level : {1, 0}) {
    const int previous = set_image_kernel_limit(level);
    const double t = best_ms(5, [&] { apply_to_image(m, in.data(), n, out.data()); });
    set_image_kernel_limit(previous);
    std::printf("  apply root-poly 2 (%s kernel) %8.2f ms = %.0f %% of memcpy speed\n", level ? "AVX2" : "SSE2", t,
                100.0 * t_copy / t);
    std::printf("BENCH apply_24MP root-poly-2-%s %.2f\n", level ? "avx2" : "sse2", t);
  }
#endif
  return 0;
}

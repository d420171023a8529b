// Timing and memory helpers shared by the benchmarks (tests/bench/bench_*.cpp). The figures they
// print are read by scripts/bench.sh: "BENCH <case> <step> <ms>" and "PEAK <case> <MiB>".
#pragma once
#include <algorithm>
#include <chrono>

#include "tristim/memory.hpp"

#ifdef __EMSCRIPTEN__
#include <emscripten/heap.h>
#else
#include <sys/resource.h>
#endif

namespace tristim::bench {

using Clock = std::chrono::steady_clock;

/// The CLI's memory policy (keep_freed_memory, set in its main) in every benchmark, before main:
/// natively freed images are reused as the wasm heap reuses them.
[[maybe_unused]] static const bool kMemoryPolicy = (keep_freed_memory(), true);

/// Peak memory so far, MiB: the wasm heap's size (it only grows, so its size is the peak), or
/// natively the process's peak resident set.
inline double peak_mib() {
#ifdef __EMSCRIPTEN__
  return emscripten_get_heap_size() / 1048576.0;
#else
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
#endif
}

/// Which build runs the benchmark: "wasm" or "native" (the word scripts/bench.sh pairs rows by).
inline const char* build_name() {
#ifdef __EMSCRIPTEN__
  return "wasm";
#else
  return "native";
#endif
}

/// Milliseconds since t0.
inline double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// Milliseconds one call of f takes.
template <class F>
double time_ms(F&& f) {
  const auto t0 = Clock::now();
  f();
  return ms_since(t0);
}

/// The fastest of `reps` calls of f, ms.
template <class F>
double best_ms(int reps, F&& f) {
  double best = 1e300;
  for (int i = 0; i < reps; ++i) best = std::min(best, time_ms(f));
  return best;
}

}  // namespace tristim::bench

// Sums in one order of additions in both builds: four partial sums (lane = index mod 4), added at
// the end as (s0 + s1) + (s2 + s3). Eigen's reductions and products group their additions by the
// SIMD width, which differs between SSE2 natively and wasm's scalar path, so an optimiser fed by
// them took other steps in the page than in the CLI. The four chains are independent, which the
// compilers vectorise. Used by the surface fits (the Phase I objective; Phase II's sums).
#pragma once
#include <cstddef>

namespace tristim {

/// Four partial sums carried across several add() calls (e.g. one per patch).
struct Sum4 {
  double s[4] = {0, 0, 0, 0};
  /// Adds term(i) for 0 <= i < n, term(i) to partial sum i mod 4.
  template <class Term>
  void add(std::ptrdiff_t n, Term term) {
    std::ptrdiff_t i = 0;
    for (; i + 4 <= n; i += 4)
      for (int j = 0; j < 4; ++j) s[j] += term(i + j);
    for (; i < n; ++i) s[i & 3] += term(i);
  }
  double total() const { return (s[0] + s[1]) + (s[2] + s[3]); }
};

/// Σ term(i) for 0 <= i < n, in Sum4's order.
template <class Term>
double sum4(std::ptrdiff_t n, Term term) {
  Sum4 a;
  a.add(n, term);
  return a.total();
}

}  // namespace tristim

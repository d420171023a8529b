// The percentile of a sample of float pixel values, for image statistics (the RAW preview's
// white point, chart detection's levels): the order statistic at floor(p (n − 1)), found by
// nth_element (O(n), reorders v). The same element natively and in wasm, since the rank is fixed
// whatever order nth_element leaves the rest in. (Figures that are reported use evaluation's
// quantile, which interpolates between order statistics.)
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace tristim {

/// The p-th percentile (0 <= p <= 1) of v as its order statistic floor(p (n − 1)); 0 for an
/// empty v. Reorders v.
inline float percentile(std::vector<float>& v, double p) {
  if (v.empty()) return 0.f;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace tristim

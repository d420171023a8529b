// Large per-pixel buffers: decoded images (72 MB of linear RGB at 24 MP), dark and flat frames,
// calibrated copies, the absolute chain's accumulators (~190 MB for a 24 MP bracket) and X, Y, Z.
// Memory fresh from the system costs one page fault per 4 KiB page on first touch (measured
// ~20 µs each on a virtual machine: ~0.9 s for 168 MB); on Linux the kernel is asked for
// transparent huge pages (MADV_HUGEPAGE) before the first touch, one fault per 2 MiB. Elsewhere
// (wasm, other systems) a plain assign.
#pragma once
#include <cstdint>
#include <vector>

#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <sys/mman.h>
#endif

namespace tristim::detail {

/// Empties v and reserves room for n elements in fresh memory, advised for huge pages when it is
/// large (≥ 4 MiB); nothing is touched yet.
template <class T>
void reserve_large(std::vector<T>& v, std::size_t n) {
  std::vector<T>().swap(v);
  v.reserve(n);
#if defined(__linux__) && !defined(__EMSCRIPTEN__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t(1) << 21;
  if (n * sizeof(T) >= (std::size_t(4) << 20)) {
    const auto begin = (reinterpret_cast<std::uintptr_t>(v.data()) + huge - 1) & ~(huge - 1);
    const auto end = reinterpret_cast<std::uintptr_t>(v.data() + n) & ~(huge - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // advice only: failure is harmless
  }
#endif
}

/// v = n copies of value, in fresh memory advised for huge pages when it is large (≥ 4 MiB).
template <class T>
void assign_large(std::vector<T>& v, std::size_t n, T value) {
  reserve_large(v, n);
  v.assign(n, value);
}

/// v = a copy of `from`, in fresh memory advised for huge pages when it is large (≥ 4 MiB).
template <class T>
void copy_large(std::vector<T>& v, const std::vector<T>& from) {
  reserve_large(v, from.size());
  v.assign(from.begin(), from.end());
}

}  // namespace tristim::detail

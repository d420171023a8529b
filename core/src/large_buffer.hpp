// Large per-pixel buffers: decoded images (72 MB of linear RGB at 24 MP), dark and flat frames,
// calibrated copies, the absolute chain's accumulators (~190 MB for a 24 MP bracket) and X, Y, Z.
// Memory fresh from the system costs a page fault per 4 KiB page at first touch. On Linux the
// kernel is asked to map and zero the pages of a large buffer in one call before it is filled
// (MADV_POPULATE_WRITE, Linux 5.14+; older kernels refuse it and the pages fault as usual): a
// 72 MB buffer filled in 19–27 ms instead of 32–41 ms on an Intel Xeon VM. Not huge pages: with
// MADV_HUGEPAGE a kernel whose THP defrag policy is "madvise" (the default)
// compacts memory in the faulting thread, and once the machine's memory was fragmented that cost
// up to 0.8 s per 256 MB (24 MP dark + flat frames in 99–510 ms, 50 MP in ~1 s, against a steady
// 130 ms and 270 ms with 4 KiB pages). Elsewhere (wasm, other systems) a plain assign.
#pragma once
#include <cstdint>
#include <vector>

#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace tristim::detail {

#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#ifdef MADV_POPULATE_WRITE
constexpr int kPopulateWrite = MADV_POPULATE_WRITE;
#else
constexpr int kPopulateWrite = 23;  // Linux 5.14's value; older kernels refuse it (EINVAL), harmlessly
#endif
#endif

/// Empties v and reserves room for n elements; when that is large (≥ 4 MiB) and fresh, natively
/// on Linux the pages are mapped (zeroed by the kernel) in one call. The elements are not constructed.
template <class T>
void reserve_large(std::vector<T>& v, std::size_t n) {
  std::vector<T>().swap(v);
  v.reserve(n);
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
  static const std::uintptr_t page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  if (n * sizeof(T) >= (std::size_t(4) << 20)) {
    const auto begin = (reinterpret_cast<std::uintptr_t>(v.data()) + page - 1) & ~(page - 1);
    const auto end = reinterpret_cast<std::uintptr_t>(v.data() + n) & ~(page - 1);
    // Memory the process used before (glibc hands freed blocks back out; keep_freed_memory) is
    // mapped already, and populating it again still walks every page (2-8 ms for 72-150 MB):
    // only a range whose first or last page is not resident is populated.
    const auto resident = [](std::uintptr_t a) {
      unsigned char in_core = 0;
      return mincore(reinterpret_cast<void*>(a), 1, &in_core) == 0 && (in_core & 1) != 0;
    };
    if (end > begin && (!resident(begin) || !resident(end - page)))
      madvise(reinterpret_cast<void*>(begin), end - begin, kPopulateWrite);  // advice only: failure is harmless
  }
#endif
}

/// v = n copies of value, in memory reserved by reserve_large.
template <class T>
void assign_large(std::vector<T>& v, std::size_t n, T value) {
  reserve_large(v, n);
  v.assign(n, value);
}

/// v = a copy of `from`, in memory reserved by reserve_large.
template <class T>
void copy_large(std::vector<T>& v, const std::vector<T>& from) {
  reserve_large(v, from.size());
  v.assign(from.begin(), from.end());
}

}  // namespace tristim::detail

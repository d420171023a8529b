// Process-wide memory policy (tristim/memory.hpp).
#include "tristim/memory.hpp"

#include <climits>  // first: defines __GLIBC__ (through <features.h>) on glibc systems

#if defined(__GLIBC__) && !defined(__EMSCRIPTEN__)
#include <malloc.h>
#endif

namespace tristim {

void keep_freed_memory() {
#if defined(__GLIBC__) && !defined(__EMSCRIPTEN__)
  mallopt(M_MMAP_MAX, 0);              // large blocks from the heap, reused after free (not munmap'd)
  mallopt(M_TRIM_THRESHOLD, INT_MAX);  // never shrink the heap: freed pages stay touched
#endif
}

}  // namespace tristim

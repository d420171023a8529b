// tristim — process-wide memory policy for programs that handle full-size images one after another.
#pragma once

namespace tristim {

/// Keeps memory freed by large buffers (decoded images, dark and flat frames, calibrated copies)
/// in the process for the next allocation instead of returning it to the system (glibc: no
/// mmap for large blocks, no trimming of the heap). The wasm heap behaves so already: it never
/// shrinks. Why natively: on a virtual machine the first touch of memory fresh from the system
/// costs a page fault per page (measured ~3–10 ms per MB on a 2-core VM), so a 24 MP RAW decoded
/// and calibrated into fresh buffers spends most of its time in the kernel. Memory is not
/// given back until exit, so the resident size stays at its peak. Call it once, early, from
/// main() (the CLI and the benchmarks do); a no-op in wasm and outside glibc.
void keep_freed_memory();

}  // namespace tristim

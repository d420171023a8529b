// Stated resource limits of the readers (issue 14). An input beyond one of them is refused with
// Error(LimitExceeded) naming the limit, before the work or memory it would take; the numbers are
// generous for every real chart, profile and recipe, and keep the worst case bounded (natively and
// in the page's 2 GB wasm heap).
//
// Memory: a text file within kMaxTextFileBytes is held as text, lines and cells at once, at most
// ~10× its size (measured: see /tests/core/io/limits_test.cpp); a JSON document within
// kMaxJsonBytes holds at most kMaxJsonValues values of ~100 bytes each (≤ 25 MB), whatever the file.
#pragma once
#include <cstddef>

namespace tristim::limits {

// --- patch and spectral tables (CSV, CGATS): io/patch_files.hpp
constexpr std::size_t kMaxTextFileBytes = 32u << 20;  ///< 32 MiB of CSV / CGATS text
constexpr std::size_t kMaxTableRows = 100000;         ///< data rows (patches, or wavelengths)
constexpr std::size_t kMaxTableColumns = 2000;        ///< columns (1 nm spectra 380-780 need 402)

// --- JSON (profiles, recipes): io/json.hpp
constexpr std::size_t kMaxJsonBytes = 4u << 20;  ///< 4 MiB (a profile is ~5 KB)
constexpr int kMaxJsonDepth = 64;                ///< nesting of arrays and objects
constexpr std::size_t kMaxJsonArray = 100000;    ///< elements of one array or members of one object
constexpr std::size_t kMaxJsonString = 1u << 20; ///< bytes of one string
constexpr std::size_t kMaxJsonValues = 250000;   ///< values in one document
constexpr int kMaxJsonInt = 1000000000;         ///< a count or size read from JSON (patches, width, iterations)

// --- evaluation: leave-one-out of least squares is in closed form (any N); for the iterative
// objectives (psm, de2000) it refits once per patch (N fits of N − 1 patches, work ~ N²), so above
// this many patches it is skipped with a message (the fit stands).
constexpr std::size_t kMaxLeaveOneOutPatches = 2000;

// --- images: RAW decoding is capped by DecodeOptions::max_megapixels (capture/raw.hpp); image
// decoders (TIFF/PNG/JPEG) use the same figure.
constexpr double kMaxImageMegapixels = 160;

}  // namespace tristim::limits

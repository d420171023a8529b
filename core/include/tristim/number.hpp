// Below colorimetry and io alike (both read numbers with it; io includes colorimetry, never the reverse).
// Decimal text -> double, the one number reader of the core (patch files, JSON, built-in tables,
// method options). Same result and same end pointer as std::strtod in the "C" locale, bit for bit,
// but without musl's long-double scanner for the common case: in wasm that scanner runs 128-bit
// soft-float arithmetic and made reading a 45 KB spectral CSV 11x slower than natively (issue 13).
#pragma once

namespace tristim {

/// std::strtod replacement with the same contract: skips leading white space, reads the longest
/// valid prefix (decimal, hexadecimal, inf, nan), sets *end (if end is not null) past it, or to
/// `text` when nothing was read. Decimal numbers with at most 19 significant digits whose integer
/// mantissa m is at most 2^53 and whose decimal exponent e has |e| <= 22 are computed as m * 10^e
/// or m / 10^-e: both operands are exact doubles, so the one IEEE operation rounds correctly
/// (Clinger 1990, "How to read floating point numbers accurately", the fast path). Everything else
/// goes to std::strtod. tests/core/number_test.cpp compares the two on generated strings.
double parse_double(const char* text, char** end) noexcept;

namespace detail {
/// The fast path alone: true and *value, *end set when it applies; false (nothing set) when
/// parse_double would hand the text to std::strtod. For tests.
bool parse_double_fast(const char* text, double* value, const char** end) noexcept;
}  // namespace detail

}  // namespace tristim

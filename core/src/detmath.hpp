// Elementary functions that give the same bits in every build: cbrt, exp, log, pow, sin, cos, atan2
// (and log_float, a cheaper log for floats).
//
// Natively the C library's (glibc) and in wasm Emscripten's (musl) round these differently in the
// last place for many arguments (cbrt: 48 % of 200,000 random arguments), so a fit
// that evaluates Lab or CIEDE2000 took other steps in the page than on the command line. These
// use only +, −, ×, ÷, sqrt and exact scaling (powers of 2 built from their bits), which IEEE 754 defines to
// the bit, in a fixed order. Nothing is fused into an FMA: x86-64's baseline target has no FMA
// instruction and wasm has none (a build for an FMA target, e.g. -march=native, would fuse and
// fail the pinned hashes in the tests). Accuracy (tests/core/colorimetry/detmath_test.cpp): exp, sin, cos,
// atan2 and pow within 2 units in the last place of the C library's result on the tested ranges, log
// within 1 (it is computed in double-double and rounded once); cbrt
// within 1 unit of the correctly rounded root (x86-64's long double as the reference: 90 % exact
// on 10^6 arguments, where glibc's cbrt is exact for 46 % and up to 3 units off). Not correctly
// rounded.
// Argument reduction for sin and cos is Cody–Waite with π/2 in three parts, exact to |x| < 2^20·π/2;
// beyond that (never reached by colour formulas) they defer to the C library.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "simd4.hpp"

namespace tristim::detmath {

namespace detail {
// π/2 in three parts: the first two with 33 significant bits, so n·part is exact for |n| < 2^20.
constexpr double kPio2_1 = 0x1.921fb54400000p+0, kPio2_2 = 0x1.0b4611a600000p-34, kPio2_3 = 0x1.3198a2e037073p-69;
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
// π, π/2 and π/6 as a double and the remainder.
constexpr double kPiHi = 0x1.921fb54442d18p+1, kPiLo = 0x1.1a62633145c07p-53;
constexpr double kPio2Hi = 0x1.921fb54442d18p+0, kPio2Lo = 0x1.1a62633145c07p-54;
constexpr double kPio4Hi = 0x1.921fb54442d18p-1;
constexpr double kPi6Hi = 0x1.0c152382d7366p-1, kPi6Lo = -0x1.ee6913347c2a6p-55;
constexpr double k3Pio4Hi = 0x1.2d97c7f3321d2p+1;
constexpr double kSqrt3 = 0x1.bb67ae8584caap+0, kTan15 = 0x1.126145e9ecd56p-2;  // √3, 2 − √3 = tan 15°
// ln 2 with 32 significant bits (n·ln2_hi exact for |n| < 2^21) and the remainder.
constexpr double kLn2Hi = 0x1.62e42ff000000p-1, kLn2Lo = -0x1.718432a1b0e26p-35, kInvLn2 = 0x1.71547652b82fep+0;

// The integer nearest v (ties to even) for |v| < 2^51: adding and removing 1.5·2^52 rounds away
// the fraction in IEEE round-to-nearest; no call to the C library's nearbyint.
inline double round_int(double v) {
  constexpr double kShift = 0x1.8p52;
  return (v + kShift) - kShift;
}

// 2^k for −1022 ≤ k ≤ 1023, from its bits.
inline double pow2(int k) {
  const std::uint64_t bits = static_cast<std::uint64_t>(k + 1023) << 52;
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// Σ c[i] z^(N−1−i) by Horner from c[0] (the highest power) down.
template <std::size_t N>
inline double horner(double z, const double (&c)[N]) {
  double p = c[0];
  for (std::size_t i = 1; i < N; ++i) p = p * z + c[i];
  return p;
}

// Error-free transformations (IEEE round-to-nearest, no FMA): s + e = a + b exactly.
inline void fast_two_sum(double a, double b, double& s, double& e) {  // needs |a| ≥ |b| (or a = 0)
  s = a + b;
  e = b - (s - a);
}
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}
// p + e = a · b exactly (Dekker, with Veltkamp's split into 26 + 27 bits; |a|, |b| < 2^995).
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}
inline void two_prod(double a, double b, double& p, double& e) {
  p = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

// Taylor polynomials on |r| ≤ π/4 (truncation below 1e-21 relative), in z = r².
// sin r = r + r z (−1/3! + z/5! − … − z^8/19!)
constexpr double kSinCoef[9] = {-1.0 / 121645100408832000.0, 1.0 / 355687428096000.0, -1.0 / 1307674368000.0,
                                1.0 / 6227020800.0,          -1.0 / 39916800.0,       1.0 / 362880.0,
                                -1.0 / 5040.0,               1.0 / 120.0,             -1.0 / 6.0};
// cos r = 1 − (z/2 − z² (1/4! − z/6! + … + z^8/20!))
constexpr double kCosCoef[9] = {1.0 / 2432902008176640000.0, -1.0 / 6402373705728000.0, 1.0 / 20922789888000.0,
                                -1.0 / 87178291200.0,        1.0 / 479001600.0,         -1.0 / 3628800.0,
                                1.0 / 40320.0,               -1.0 / 720.0,              1.0 / 24.0};
inline double sin_poly(double r) {
  const double z = r * r;
  return r + r * z * horner(z, kSinCoef);
}
inline double cos_poly(double r) {
  const double z = r * r;
  return 1.0 - (0.5 * z - z * z * horner(z, kCosCoef));
}
// x = n·π/2 + r, |r| ≤ π/4 (a little more at rounding boundaries); false if |x| is too large.
inline bool reduce_pio2(double x, double& r, long& n) {
  if (!(std::fabs(x) < 1647099.0)) return false;  // 2^20 · π/2
  const double fn = round_int(x * kTwoOverPi);
  n = static_cast<long>(fn);
  r = ((x - fn * kPio2_1) - fn * kPio2_2) - fn * kPio2_3;
  return true;
}
// atan(t) for 0 ≤ t ≤ 1.
inline double atan01(double t) {
  double base_hi = 0, base_lo = 0, u = t;
  if (t > kTan15) {  // atan t = π/6 + atan((√3 t − 1) / (t + √3))
    u = (kSqrt3 * t - 1.0) / (t + kSqrt3);
    base_hi = kPi6Hi;
    base_lo = kPi6Lo;
  }
  // |u| ≤ 2 − √3: the series to u^31 (remainder below 1e-18 relative), Horner in u².
  static constexpr double kCoef[15] = {-1.0 / 31, 1.0 / 29, -1.0 / 27, 1.0 / 25, -1.0 / 23, 1.0 / 21, -1.0 / 19, 1.0 / 17,
                                       -1.0 / 15, 1.0 / 13, -1.0 / 11, 1.0 / 9,  -1.0 / 7,  1.0 / 5,  -1.0 / 3};
  const double z = u * u;
  const double a = u + u * z * horner(z, kCoef);
  return base_hi + (a + base_lo);
}
constexpr double kSqrt2 = 0x1.6a09e667f3bcdp+0, kLn2 = 0x1.62e42fefa39efp-1;
// log_float's series 2s(1 + s²/3 + … + s^10/11), highest power first.
constexpr double kLogFloatOdd[5] = {1.0 / 11, 1.0 / 9, 1.0 / 7, 1.0 / 5, 1.0 / 3};
// x = 2^k·m with √½ ≤ m < √2 (exact) for a normal x > 0: returns m, adds k to `k`.
inline double log_reduce(double x, int& k) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  k += static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;
  double m;
  std::memcpy(&m, &bits, sizeof m);  // [1, 2)
  if (m > kSqrt2) {
    m *= 0.5;
    ++k;
  }
  return m;
}
// ln x as hi + lo (|lo| ≤ ulp(hi)/2; about 2^-60 relative) for finite x > 0.
// x = 2^k·m with √½ ≤ m < √2; f = m − 1 (exact); ln m = 2 atanh s, s = f / (2 + f), |s| ≤ 0.1716:
// 2s in double-double plus 2s³(1/3 + s²/5 + … + s^20/23) (truncation below 5e-16 of that term,
// which is at most 1 % of the sum); k·ln 2 with ln 2 in two parts.
inline void log_dd(double x, double& hi, double& lo) {
  int k = 0;
  if (x < 0x1p-1022) {  // subnormal: scale into the normal range (exact)
    x *= 0x1p54;
    k = -54;
  }
  const double m = log_reduce(x, k);
  const double f = m - 1.0;
  double t_hi, t_lo;  // 2 + f
  fast_two_sum(2.0, f, t_hi, t_lo);
  const double inv = 1.0 / t_hi;  // one division: s_lo makes up for the rounding of s_hi
  const double s_hi = f * inv;
  double p, pe;
  two_prod(s_hi, t_hi, p, pe);
  const double s_lo = (((f - p) - pe) - s_hi * t_lo) * inv;  // f/(t_hi + t_lo) − s_hi
  static constexpr double kOdd[11] = {1.0 / 23, 1.0 / 21, 1.0 / 19, 1.0 / 17, 1.0 / 15, 1.0 / 13,
                                      1.0 / 11, 1.0 / 9,  1.0 / 7,  1.0 / 5,  1.0 / 3};
  const double z = s_hi * s_hi;
  const double tail = 2.0 * s_hi * z * horner(z, kOdd);
  // s_lo's share of the tail, 2s²·s_lo to first order (without it: 2^-58 relative).
  double lm_hi, lm_lo;  // ln m
  fast_two_sum(2.0 * s_hi, (2.0 * s_lo + 2.0 * z * s_lo) + tail, lm_hi, lm_lo);
  const double fk = k;
  double h, e;
  two_sum(fk * kLn2Hi, lm_hi, h, e);  // k·ln2_hi is exact (|k| < 1100, see kLn2Hi)
  fast_two_sum(h, e + (lm_lo + fk * kLn2Lo), hi, lo);
}

// e^(x + lo) for |lo| ≤ ulp(x): x reduced by n·ln 2, lo added to the reduced argument.
inline double exp_reduced(double x, double lo) {
  const double fn = round_int(x * kInvLn2);
  const double r = ((x - fn * kLn2Hi) - fn * kLn2Lo) + lo;  // |r| ≤ ln2 / 2 (+ rounding)
  // Taylor to r^13 / 13! (truncation below 1e-17 relative), Horner from the top.
  static constexpr double kInvFact[14] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0,
                                          1.0 / 362880.0,     1.0 / 40320.0,     1.0 / 5040.0,     1.0 / 720.0,
                                          1.0 / 120.0,        1.0 / 24.0,        1.0 / 6.0,        0.5,
                                          1.0,                1.0};
  const double p = horner(r, kInvFact);
  // × 2^n in two factors built from their bits (each a normal double for n from −1075 to 1024),
  // so only the last product rounds (a subnormal result).
  const int n = static_cast<int>(fn), h = n / 2;
  return p * pow2(h) * pow2(n - h);
}
}  // namespace detail

/// Cube root, the sign kept; ±0, ±∞ and NaN returned as given.
inline double cbrt(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  const bool negative = x < 0;
  double a = std::fabs(x), unscale = 1.0;
  // Far from 1 (and for subnormals), scale by 2^∓300 first (exact), so no cube below overflows.
  if (a > 0x1p900) {
    a *= 0x1p-300;
    unscale = 0x1p100;
  } else if (a < 0x1p-900) {
    a *= 0x1p300;
    unscale = 0x1p-100;
  }
  // Start from the bits (the exponent divided by 3: within 4 %), two Halley steps (the error
  // cubes: 6e-5, then ~1e-13) and a last Newton step, which rounds to within 1 unit.
  std::uint64_t bits;
  std::memcpy(&bits, &a, sizeof bits);
  bits = bits / 3 + 0x2a9f789300000000ULL;  // ≈ (1023 − 1023/3 − 0.033) · 2^52 (Kahan)
  double y;
  std::memcpy(&y, &bits, sizeof y);
  for (int i = 0; i < 2; ++i) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * a) / (2.0 * y3 + a);  // the ratio (near 1) first: no underflow of y · (…)
  }
  y -= (y * y * y - a) / (3.0 * y * y);
  y *= unscale;
  return negative ? -y : y;
}

/// e^x.
inline double exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.1332191019412) return 0.0;
  return detail::exp_reduced(x, 0.0);
}

/// Natural logarithm; C's conventions: ln 0 = −∞, ln x < 0 = NaN, ln ∞ = ∞.
inline double log(double x) {
  if (std::isnan(x) || x < 0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return -std::numeric_limits<double>::infinity();
  if (std::isinf(x)) return x;
  double hi, lo;
  detail::log_dd(x, hi, lo);
  return hi;
}

/// ln x of a float, as a float, for per-pixel work where log's double-double costs too much (chart
/// detection's log image: 2–3 × 10^6 values). In plain double: x = 2^k·m as in log, ln m =
/// 2s(1 + s²/3 + … + s^10/11) (truncation below 6e-11 relative), k·ln 2 + ln m rounded once to
/// float: within 1 unit in the float's last place of the true log (tested). C's conventions.
inline float log_float(float xf) {
  if (!(xf > 0.0f)) return xf == 0.0f ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::quiet_NaN();
  if (xf > std::numeric_limits<float>::max()) return xf;  // +∞
  int k = 0;
  const double m = detail::log_reduce(xf, k);  // every float, subnormals included, is a normal double
  const double f = m - 1.0, s = f / (2.0 + f), z = s * s;
  const double ln_m = 2.0 * s + 2.0 * s * z * detail::horner(z, detail::kLogFloatOdd);
  return static_cast<float>(k * detail::kLn2 + ln_m);
}

/// log_float of n values (out may be in): the same bits as log_float value by value. Four at a
/// time in two-lane doubles (SSE2 natively, SIMD128 in wasm) where all four are positive finite
/// floats, log_float's operations in its order (IEEE-exact, nothing fused); log_float elsewhere.
/// About 3× faster than log_float one by one (the chart detection's log image).
inline void log_float_n(const float* in, float* out, std::size_t n) {
  std::size_t i = 0;
#ifdef TRISTIM_SIMD4
  using namespace simd4;
  const d2 one = splat2(1.0), two = splat2(2.0), half = splat2(0.5), sqrt2 = splat2(detail::kSqrt2);
  const d2 ln2 = splat2(detail::kLn2);
  const d2 magic = bits2(0x4330000000000000ULL), magic_bias = splat2(0x1p52 + 1023.0);  // 2^52 + e − (2^52 + 1023)
  const d2 mantissa = bits2(0x000fffffffffffffULL), exponent_0 = bits2(0x3ff0000000000000ULL);
  d2 c[5];
  for (int j = 0; j < 5; ++j) c[j] = splat2(detail::kLogFloatOdd[j]);
  auto log2lanes = [&](d2 x) {  // x: positive finite floats as doubles (normal doubles)
    d2 k = sub2(bit_or2(shr64<52>(x), magic), magic_bias);  // the exponent, as log_reduce's k
    d2 m = bit_or2(bit_and2(x, mantissa), exponent_0);      // [1, 2)
    const d2 big = gt2(m, sqrt2);
    m = select2(big, mul2(m, half), m);
    k = add2(k, bit_and2(big, one));
    const d2 f = sub2(m, one), s = div2(f, add2(two, f)), z = mul2(s, s);
    d2 p = c[0];
    for (int j = 1; j < 5; ++j) p = add2(mul2(p, z), c[j]);
    const d2 s2 = mul2(two, s);
    return add2(mul2(k, ln2), add2(s2, mul2(mul2(s2, z), p)));
  };
  for (; i + 4 <= n; i += 4) {
    const f4 x = load(in + i);
    if (!all_positive_finite(x)) {
      for (int j = 0; j < 4; ++j) out[i + j] = log_float(in[i + j]);
      continue;
    }
    d2 lo, hi;
    widen(x, lo, hi);
    store(out + i, narrow(log2lanes(lo), log2lanes(hi)));
  }
#endif
  for (; i < n; ++i) out[i] = log_float(in[i]);
}

/// x^y, with C's conventions for zeros, infinities, NaN and negative x (an integer y keeps the
/// sign of an odd power, any other y gives NaN). e^(y·ln x) with ln x and the product in
/// double-double, so the result is as accurate as exp's (the error of a plain exp(y·log x) grows
/// with |y·ln x|).
inline double pow(double x, double y) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (y == 0.0 || x == 1.0) return 1.0;
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const bool y_int = std::floor(y) == y;
  const bool y_odd = y_int && std::fabs(y) < 0x1p53 && std::fmod(y, 2.0) != 0.0;
  if (std::isinf(y)) {
    const double ax = std::fabs(x);
    if (ax == 1.0) return 1.0;
    return (ax < 1.0) == (y > 0) ? 0.0 : inf;
  }
  if (x == 0.0 || std::isinf(x)) {
    const bool big = std::isinf(x) ? y > 0 : y < 0;  // ∞ or 0 as the magnitude
    const double r = big ? inf : 0.0;
    return (y_odd && std::signbit(x)) ? -r : r;
  }
  double sign = 1.0;
  if (x < 0) {
    if (!y_int) return std::numeric_limits<double>::quiet_NaN();
    if (y_odd) sign = -1.0;
    x = -x;
    if (x == 1.0) return sign;
  }
  if (std::fabs(y) > 0x1p900) return sign * ((x < 1.0) == (y > 0) ? 0.0 : inf);  // |y·ln x| > 2^846
  double lh, ll, ph, pe, zh, zl;
  detail::log_dd(x, lh, ll);
  detail::two_prod(y, lh, ph, pe);
  detail::fast_two_sum(ph, pe + y * ll, zh, zl);
  if (zh > 709.782712893384) return sign * inf;
  if (zh < -745.1332191019412) return sign * 0.0;
  return sign * detail::exp_reduced(zh, zl);
}

/// sin x (x in radians).
inline double sin(double x) {
  if (!std::isfinite(x)) return x - x;  // NaN
  if (x == 0.0) return x;               // ±0
  double r;
  long n;
  if (!detail::reduce_pio2(x, r, n)) return std::sin(x);
  switch (n & 3) {
    case 0: return detail::sin_poly(r);
    case 1: return detail::cos_poly(r);
    case 2: return -detail::sin_poly(r);
    default: return -detail::cos_poly(r);
  }
}

/// cos x (x in radians).
inline double cos(double x) {
  if (!std::isfinite(x)) return x - x;
  double r;
  long n;
  if (!detail::reduce_pio2(x, r, n)) return std::cos(x);
  switch (n & 3) {
    case 0: return detail::cos_poly(r);
    case 1: return -detail::sin_poly(r);
    case 2: return -detail::cos_poly(r);
    default: return detail::sin_poly(r);
  }
}

/// atan2(y, x) in (−π, π], with C's conventions for zeros, infinities and NaN.
inline double atan2(double y, double x) {
  using namespace detail;
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (std::isinf(x)) {
    if (std::isinf(y)) return std::copysign(x > 0 ? kPio4Hi : k3Pio4Hi, y);
    return std::copysign(x > 0 ? 0.0 : kPiHi, y);
  }
  if (std::isinf(y)) return std::copysign(kPio2Hi, y);
  if (y == 0.0) return (x > 0 || (x == 0.0 && !std::signbit(x))) ? y : std::copysign(kPiHi, y);
  if (x == 0.0) return std::copysign(kPio2Hi, y);
  const double ay = std::fabs(y), ax = std::fabs(x);
  double a;  // atan(ay / ax) in [0, π/2]
  if (ay <= ax) {
    a = atan01(ay / ax);
  } else {
    a = kPio2Hi - (atan01(ax / ay) - kPio2Lo);
  }
  if (x < 0) a = kPiHi - (a - kPiLo);
  return std::copysign(a, y);
}

}  // namespace tristim::detmath

// Four-lane float vectors for the per-pixel image kernels: SSE2 natively on x86, SIMD128 in wasm
// (-msimd128, set for the wasm build in CMakeLists.txt; Node 16.4+, Chromium 91+, Firefox 89+). The operations are
// plain IEEE ones (add, mul, div, correctly rounded sqrt, no FMA), so the same kernel gives
// bit-identical results on both targets, and the scalar loop's. Also two-lane doubles (d2: add,
// mul, div, compare, bit operations, float <-> double), for a kernel that works in double on float
// data (detmath::log_float_n). The SSE2 and SIMD128 halves below are the same API written twice,
// one per target.
// TRISTIM_SIMD4 is undefined elsewhere: callers keep a scalar path.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#define TRISTIM_SIMD4 1
#elif defined(__wasm_simd128__)
#include <wasm_simd128.h>
#define TRISTIM_SIMD4 1
#endif

#ifdef TRISTIM_SIMD4
namespace tristim::simd4 {

/// Bytes ahead of the current pixel that the image kernels ask the CPU to fetch: the loops read
/// the input sequentially, yet on an Intel Xeon VM the hardware prefetcher alone kept the
/// AVX-512 root-polynomial kernel waiting on memory (42 ms for 24 MP, with compute alone 19 ms
/// and memory alone 28 ms; 31 ms with this prefetch 6 KB ahead).
constexpr std::ptrdiff_t kPrefetchAhead = 6144;

#if defined(__SSE2__)
using f4 = __m128;
/// Asks for the cache line kPrefetchAhead bytes past p (never faults, even past the buffer's end).
inline void prefetch_ahead(const float* p) {
  _mm_prefetch(reinterpret_cast<const char*>(p) + kPrefetchAhead, _MM_HINT_T0);
}
inline f4 splat(float v) { return _mm_set1_ps(v); }
inline f4 add(f4 a, f4 b) { return _mm_add_ps(a, b); }
inline f4 mul(f4 a, f4 b) { return _mm_mul_ps(a, b); }
inline f4 sub(f4 a, f4 b) { return _mm_sub_ps(a, b); }
/// Every lane holds the 32-bit pattern v (e.g. ~0u: a mask of all ones).
inline f4 bits(std::uint32_t v) { return _mm_castsi128_ps(_mm_set1_epi32(static_cast<int>(v))); }
inline f4 bit_and(f4 a, f4 b) { return _mm_and_ps(a, b); }
inline f4 bit_or(f4 a, f4 b) { return _mm_or_ps(a, b); }
/// All ones in the lanes where a >= b, zeros elsewhere.
inline f4 ge(f4 a, f4 b) { return _mm_cmpge_ps(a, b); }
/// std::min(a, b) and std::max(a, b) lane by lane, NaN cases included ((b < a) ? b : a, (a < b) ? b : a).
inline f4 min_std(f4 a, f4 b) { return _mm_min_ps(b, a); }
inline f4 max_std(f4 a, f4 b) { return _mm_max_ps(b, a); }
inline f4 le(f4 a, f4 b) { return _mm_cmple_ps(a, b); }
inline f4 gt(f4 a, f4 b) { return _mm_cmpgt_ps(a, b); }
inline f4 div(f4 a, f4 b) { return _mm_div_ps(a, b); }
/// Bit i set when lane i of a comparison's mask is set.
inline int mask_bits(f4 mask) { return _mm_movemask_ps(mask); }
inline f4 sqrt(f4 a) { return _mm_sqrt_ps(a); }
/// x with the lanes of `mask` cleared; mask ? a : b.
inline f4 and_not(f4 x, f4 mask) { return _mm_andnot_ps(mask, x); }
inline f4 select(f4 mask, f4 a, f4 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }
inline f4 load(const float* p) { return _mm_loadu_ps(p); }
inline void store(float* p, f4 v) { _mm_storeu_ps(p, v); }
/// All ones in the lanes where the 32-bit integers are equal.
inline f4 int_eq(f4 a, f4 b) { return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_castps_si128(a), _mm_castps_si128(b))); }
/// Four bytes p[0..3] as the 32-bit integers of the four lanes.
inline f4 load_bytes(const std::uint8_t* p) {
  std::int32_t four;
  std::memcpy(&four, p, 4);
  const __m128i z = _mm_setzero_si128();
  return _mm_castsi128_ps(_mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(four), z), z));
}
/// Eight little-endian uint16 (16 bytes, any alignment) -> the four at even and the four at odd
/// indices, as floats (exact).
inline void load_u16_pairs(const std::uint16_t* p, f4& even, f4& odd) {
  const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  even = _mm_cvtepi32_ps(_mm_and_si128(x, _mm_set1_epi32(0xffff)));
  odd = _mm_cvtepi32_ps(_mm_srli_epi32(x, 16));
}
/// Each lane's 32-bit integer (0..255) as one byte: out[0..3].
inline void store_bytes(std::uint8_t* out, f4 v) {
  const __m128i w = _mm_castps_si128(v);
  const __m128i b = _mm_packus_epi16(_mm_packs_epi32(w, w), w);
  const std::int32_t four = _mm_cvtsi128_si32(b);
  std::memcpy(out, &four, 4);
}

/// Lanes a[i0] a[i1] b[j0] b[j1] (x86's shufps).
template <int i0, int i1, int j0, int j1>
inline f4 shufps(f4 a, f4 b) { return _mm_shuffle_ps(a, b, _MM_SHUFFLE(j1, j0, i1, i0)); }
/// a0 b0 a1 b1 and a2 b2 a3 b3 (x86's unpcklps, unpckhps).
inline f4 unpacklo(f4 a, f4 b) { return _mm_unpacklo_ps(a, b); }
inline f4 unpackhi(f4 a, f4 b) { return _mm_unpackhi_ps(a, b); }
/// Two-lane doubles (SSE2 / SIMD128 f64x2), for kernels that work in double on float data.
using d2 = __m128d;
inline d2 splat2(double v) { return _mm_set1_pd(v); }
inline d2 add2(d2 a, d2 b) { return _mm_add_pd(a, b); }
inline d2 sub2(d2 a, d2 b) { return _mm_sub_pd(a, b); }
inline d2 mul2(d2 a, d2 b) { return _mm_mul_pd(a, b); }
inline d2 div2(d2 a, d2 b) { return _mm_div_pd(a, b); }
/// All ones in the lanes where a > b.
inline d2 gt2(d2 a, d2 b) { return _mm_cmpgt_pd(a, b); }
inline d2 bit_and2(d2 a, d2 b) { return _mm_and_pd(a, b); }
inline d2 bit_or2(d2 a, d2 b) { return _mm_or_pd(a, b); }
/// Every lane holds the 64-bit pattern v.
inline d2 bits2(std::uint64_t v) { return _mm_castsi128_pd(_mm_set1_epi64x(static_cast<long long>(v))); }
/// The 64-bit lanes shifted right by n bits (zeros in).
template <int n>
inline d2 shr64(d2 a) { return _mm_castsi128_pd(_mm_srli_epi64(_mm_castpd_si128(a), n)); }
/// mask ? a : b, lane by lane.
inline d2 select2(d2 mask, d2 a, d2 b) { return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b)); }
/// True when every lane is a positive finite float (not ±0, negative, ∞ or NaN).
inline bool all_positive_finite(f4 x) {
  const f4 ok = _mm_and_ps(_mm_cmpgt_ps(x, _mm_setzero_ps()), _mm_cmple_ps(x, _mm_set1_ps(3.40282347e+38f)));
  return _mm_movemask_ps(ok) == 0xf;
}
/// Floats 0-1 and 2-3 as doubles (exact).
inline void widen(f4 x, d2& lo, d2& hi) {
  lo = _mm_cvtps_pd(x);
  hi = _mm_cvtps_pd(_mm_movehl_ps(x, x));
}
/// Each double rounded to float (to nearest), lanes lo0 lo1 hi0 hi1.
inline f4 narrow(d2 lo, d2 hi) { return _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi)); }
#else  // wasm SIMD128
using f4 = v128_t;
/// wasm has no prefetch instruction (a plain load of data ahead waits for it: no help natively).
inline void prefetch_ahead(const float*) {}
inline f4 splat(float v) { return wasm_f32x4_splat(v); }
inline f4 add(f4 a, f4 b) { return wasm_f32x4_add(a, b); }
inline f4 mul(f4 a, f4 b) { return wasm_f32x4_mul(a, b); }
inline f4 sub(f4 a, f4 b) { return wasm_f32x4_sub(a, b); }
inline f4 bits(std::uint32_t v) { return wasm_i32x4_splat(static_cast<std::int32_t>(v)); }
inline f4 bit_and(f4 a, f4 b) { return wasm_v128_and(a, b); }
inline f4 bit_or(f4 a, f4 b) { return wasm_v128_or(a, b); }
inline f4 ge(f4 a, f4 b) { return wasm_f32x4_ge(a, b); }
inline f4 min_std(f4 a, f4 b) { return wasm_f32x4_pmin(a, b); }
inline f4 max_std(f4 a, f4 b) { return wasm_f32x4_pmax(a, b); }
inline f4 le(f4 a, f4 b) { return wasm_f32x4_le(a, b); }
inline f4 gt(f4 a, f4 b) { return wasm_f32x4_gt(a, b); }
inline f4 div(f4 a, f4 b) { return wasm_f32x4_div(a, b); }
inline int mask_bits(f4 mask) { return static_cast<int>(wasm_i32x4_bitmask(mask)); }
inline f4 sqrt(f4 a) { return wasm_f32x4_sqrt(a); }
inline f4 and_not(f4 x, f4 mask) { return wasm_v128_andnot(x, mask); }
inline f4 select(f4 mask, f4 a, f4 b) { return wasm_v128_bitselect(a, b, mask); }
inline f4 load(const float* p) { return wasm_v128_load(p); }
inline void store(float* p, f4 v) { wasm_v128_store(p, v); }
inline f4 int_eq(f4 a, f4 b) { return wasm_i32x4_eq(a, b); }
inline f4 load_bytes(const std::uint8_t* p) {
  std::int32_t four;
  std::memcpy(&four, p, 4);
  return wasm_u32x4_extend_low_u16x8(wasm_u16x8_extend_low_u8x16(wasm_i32x4_make(four, 0, 0, 0)));
}
inline void load_u16_pairs(const std::uint16_t* p, f4& even, f4& odd) {
  const v128_t x = wasm_v128_load(p);
  even = wasm_f32x4_convert_i32x4(wasm_v128_and(x, wasm_i32x4_splat(0xffff)));
  odd = wasm_f32x4_convert_i32x4(wasm_u32x4_shr(x, 16));
}
inline void store_bytes(std::uint8_t* out, f4 v) {
  const v128_t h = wasm_i16x8_narrow_i32x4(v, v);
  const std::int32_t four = wasm_i32x4_extract_lane(wasm_u8x16_narrow_i16x8(h, h), 0);
  std::memcpy(out, &four, 4);
}

// shufps and unpcklps/unpckhps as the two-operand shuffles V8 emits as those single x86
// instructions, where an arbitrary two-operand shuffle costs two pshufb and a por.
template <int i0, int i1, int j0, int j1>
inline f4 shufps(f4 a, f4 b) { return wasm_i32x4_shuffle(a, b, i0, i1, 4 + j0, 4 + j1); }
inline f4 unpacklo(f4 a, f4 b) { return wasm_i32x4_shuffle(a, b, 0, 4, 1, 5); }
inline f4 unpackhi(f4 a, f4 b) { return wasm_i32x4_shuffle(a, b, 2, 6, 3, 7); }

using d2 = v128_t;
inline d2 splat2(double v) { return wasm_f64x2_splat(v); }
inline d2 add2(d2 a, d2 b) { return wasm_f64x2_add(a, b); }
inline d2 sub2(d2 a, d2 b) { return wasm_f64x2_sub(a, b); }
inline d2 mul2(d2 a, d2 b) { return wasm_f64x2_mul(a, b); }
inline d2 div2(d2 a, d2 b) { return wasm_f64x2_div(a, b); }
inline d2 gt2(d2 a, d2 b) { return wasm_f64x2_gt(a, b); }
inline d2 bit_and2(d2 a, d2 b) { return wasm_v128_and(a, b); }
inline d2 bit_or2(d2 a, d2 b) { return wasm_v128_or(a, b); }
inline d2 bits2(std::uint64_t v) { return wasm_i64x2_splat(static_cast<std::int64_t>(v)); }
template <int n>
inline d2 shr64(d2 a) { return wasm_u64x2_shr(a, n); }
inline d2 select2(d2 mask, d2 a, d2 b) { return wasm_v128_bitselect(a, b, mask); }
inline bool all_positive_finite(f4 x) {
  return wasm_i32x4_all_true(
      wasm_v128_and(wasm_f32x4_gt(x, wasm_f32x4_splat(0.0f)), wasm_f32x4_le(x, wasm_f32x4_splat(3.40282347e+38f))));
}
inline void widen(f4 x, d2& lo, d2& hi) {
  lo = wasm_f64x2_promote_low_f32x4(x);
  hi = wasm_f64x2_promote_low_f32x4(wasm_i32x4_shuffle(x, x, 2, 3, 2, 3));
}
inline f4 narrow(d2 lo, d2 hi) {
  return wasm_i32x4_shuffle(wasm_f32x4_demote_f64x2_zero(lo), wasm_f32x4_demote_f64x2_zero(hi), 0, 1, 4, 5);
}
#endif

// Written once from the operations above (the same instructions on both targets as when each
// target spelled them out).

/// sign(p)·sqrt(|p|), lane by lane (correctly rounded sqrt).
inline f4 signed_sqrt(f4 p) {
  const f4 sign = splat(-0.0f);
  return bit_or(sqrt(and_not(p, sign)), bit_and(sign, p));
}
/// Four interleaved RGB pixels (12 floats) -> planar R, G, B.
inline void load_rgb(const float* in, f4& R, f4& G, f4& B) {
  const f4 a = load(in), b = load(in + 4), c = load(in + 8);
  const f4 t0 = shufps<1, 2, 0, 1>(a, b);  // g0 b0 g1 b1
  const f4 t1 = shufps<2, 3, 1, 2>(b, c);  // r2 g2 r3 g3
  R = shufps<0, 3, 0, 2>(a, t1);
  G = shufps<0, 2, 1, 3>(t0, t1);
  B = shufps<1, 3, 0, 3>(t0, c);
}
/// Planar X, Y, Z -> four interleaved pixels (12 floats).
inline void store_xyz(float* out, f4 X, f4 Y, f4 Z) {
  const f4 lo = unpacklo(X, Y), hi = unpackhi(X, Y);  // x0 y0 x1 y1 | x2 y2 x3 y3
  const f4 a = shufps<0, 0, 2, 2>(Z, lo);             // z0 z0 x1 x1
  const f4 b = shufps<3, 3, 1, 1>(lo, Z);             // y1 y1 z1 z1
  const f4 c = shufps<2, 2, 2, 2>(Z, hi);             // z2 z2 x3 x3
  const f4 d = shufps<3, 3, 3, 3>(hi, Z);             // y3 y3 z3 z3
  store(out, shufps<0, 1, 0, 2>(lo, a));              // x0 y0 z0 x1
  store(out + 4, shufps<0, 2, 0, 1>(b, hi));          // y1 z1 x2 y2
  store(out + 8, shufps<0, 2, 0, 2>(c, d));           // z2 x3 y3 z3
}

}  // namespace tristim::simd4
#endif

// Whole-image application of a model (apply_to_image): 4-lane kernels (SSE2 natively, SIMD128
// in wasm; simd4.hpp) for the 3×3, affine and degree-2 root-polynomial models; natively, chosen at
// run time, AVX-512 variants of the affine and root-polynomial kernels and an AVX2+FMA variant of
// the root-polynomial; scalar loops with the same association for the tails, a generic double
// path for the rest. The affine kernels (all widths) and the 4-lane root-polynomial use only
// IEEE add, mul and sqrt: bit-identical to the scalar loops, native and wasm alike (this file is
// compiled with -ffp-contract=off so that stays true in the AVX-512 functions). The AVX2 and
// AVX-512 root-polynomials fuse multiply-adds, the same lane for lane (identical floats to each
// other), and differ from the scalar loop by FMA rounding (tests/core/characterisation/models_test.cpp).
// In place (out == in) is allowed: every kernel reads a step's pixels before it writes them, so
// the buffers are not declared __restrict.
// Plain stores, except the AVX-512 kernels' on large outputs: on an AMD EPYC VM 16-byte
// non-temporal stores made the 24 MP apply slower (3×3 at 63 % of memcpy speed with them, 93 %
// without; root-polynomial AVX2 47 % vs 65 %); on an Intel Xeon VM the AVX-512 kernel's
// whole-line (64-byte, aligned) non-temporal stores are faster than its plain ones. Natively every
// kernel asks for its input 6 KB ahead (simd4::prefetch_ahead: the Intel VM's
// hardware prefetcher alone left the 24 MP apply waiting on memory).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "../simd4.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

inline float signed_sqrt1(float p) {
  const float r = std::sqrt(p < 0.f ? -p : p);
  return p < 0.f ? -r : r;
}

// Scalar loops, associated as the 4-lane kernels are (bit-identical to them): the tails of the
// vector loops, and every pixel where there is no SIMD.
void scalar_affine(const float* in, size_t n, float* out, const float (&a)[3][4]) {
  for (size_t i = 0; i < n; ++i) {
    const float R = in[3 * i], G = in[3 * i + 1], B = in[3 * i + 2];
    for (int c = 0; c < 3; ++c) out[3 * i + c] = (a[c][0] * R + a[c][1] * G) + (a[c][2] * B + a[c][3]);
  }
}
void scalar_root2(const float* in, size_t n, float* out, const float (&a)[3][6]) {
  for (size_t i = 0; i < n; ++i) {
    const float R = in[3 * i], G = in[3 * i + 1], B = in[3 * i + 2];
    const float P = signed_sqrt1(R * G), Q = signed_sqrt1(R * B), S = signed_sqrt1(G * B);
    for (int c = 0; c < 3; ++c)
      out[3 * i + c] = ((a[c][0] * R + a[c][1] * G) + (a[c][2] * B + a[c][3] * P)) + (a[c][4] * Q + a[c][5] * S);
  }
}

#ifdef TRISTIM_SIMD4
// Fused 4-lane loops, 4 pixels per step straight from and to the interleaved buffers; return how
// many pixels they handled (a multiple of 4); the caller finishes the tail.
size_t simd_affine(const float* in, size_t n, float* out, const float (&a)[3][4]) {
  using namespace simd4;
  f4 k[3][4];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 4; ++j) k[c][j] = splat(a[c][j]);
  const size_t m = n & ~size_t(3);
  for (size_t i = 0; i < m; i += 4) {
    prefetch_ahead(in + 3 * i);  // one line per 48-byte step: every line at least once
    f4 R, G, B;
    load_rgb(in + 3 * i, R, G, B);
    f4 o[3];
    for (int c = 0; c < 3; ++c) o[c] = add(add(mul(k[c][0], R), mul(k[c][1], G)), add(mul(k[c][2], B), k[c][3]));
    store_xyz(out + 3 * i, o[0], o[1], o[2]);
  }
  return m;
}

// True when no lane of R, G or B has its sign bit set: then every product of two of them is +0,
// positive or NaN, and sqrt alone gives signed_sqrt's floats (sqrt(+0) = +0; a NaN stays the same
// NaN). Skipping the sign's masking on such steps (the sign test costs two ORs and a movemask):
// 24 MP on an AMD EPYC VM, ~12 % faster in wasm (V8 spends its registers on the 18 coefficients)
// and ~10 % natively with SSE2.
inline bool no_sign_bit(simd4::f4 R, simd4::f4 G, simd4::f4 B) {
  return simd4::mask_bits(simd4::bit_or(simd4::bit_or(R, G), B)) == 0;
}

size_t simd_root2(const float* in, size_t n, float* out, const float (&a)[3][6]) {
  using namespace simd4;
  f4 k[3][6];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 6; ++j) k[c][j] = splat(a[c][j]);
  const size_t m = n & ~size_t(3);
  for (size_t i = 0; i < m; i += 4) {
    prefetch_ahead(in + 3 * i);
    f4 R, G, B;
    load_rgb(in + 3 * i, R, G, B);
    f4 P, Q, S;
    if (no_sign_bit(R, G, B)) {  // the usual pixel: plain square roots, the same floats
      P = sqrt(mul(R, G));
      Q = sqrt(mul(R, B));
      S = sqrt(mul(G, B));
    } else {
      P = signed_sqrt(mul(R, G));
      Q = signed_sqrt(mul(R, B));
      S = signed_sqrt(mul(G, B));
    }
    f4 o[3];
    for (int c = 0; c < 3; ++c)
      o[c] = add(add(add(mul(k[c][0], R), mul(k[c][1], G)), add(mul(k[c][2], B), mul(k[c][3], P))),
                 add(mul(k[c][4], Q), mul(k[c][5], S)));
    store_xyz(out + 3 * i, o[0], o[1], o[2]);
  }
  return m;
}

#if defined(__x86_64__) && defined(__SSE2__) && (defined(__GNUC__) || defined(__clang__))
// AVX2 + FMA variant of the root-polynomial loop (8 pixels per step: two SSE deinterleaves, the
// arithmetic 8-wide), chosen at run time when the CPU has them; the binary stays baseline x86-64.
#define TRISTIM_HAVE_AVX2_PATH 1
__attribute__((target("avx2,fma"))) inline __m256 signed_sqrt8(__m256 p) {
  const __m256 sign = _mm256_set1_ps(-0.0f);
  return _mm256_or_ps(_mm256_sqrt_ps(_mm256_andnot_ps(sign, p)), _mm256_and_ps(sign, p));
}
__attribute__((target("avx2,fma"))) inline __m256 join8(__m128 lo, __m128 hi) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
}
__attribute__((target("avx2,fma"))) size_t avx2_root2(const float* in, size_t n,
                                                        float* out, const float (&a)[3][6]) {
  __m256 k[3][6];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 6; ++j) k[c][j] = _mm256_set1_ps(a[c][j]);
  const size_t m = n & ~size_t(7);
  for (size_t i = 0; i < m; i += 8) {
    simd4::prefetch_ahead(in + 3 * i);  // 96 bytes per step: two lines
    simd4::prefetch_ahead(in + 3 * i + 16);
    __m128 R0, G0, B0, R1, G1, B1;
    simd4::load_rgb(in + 3 * i, R0, G0, B0);
    simd4::load_rgb(in + 3 * i + 12, R1, G1, B1);
    const __m256 R = join8(R0, R1), G = join8(G0, G1), B = join8(B0, B1);
    __m256 P, Q, S;
    if (_mm256_movemask_ps(_mm256_or_ps(_mm256_or_ps(R, G), B)) == 0) {  // as no_sign_bit
      P = _mm256_sqrt_ps(_mm256_mul_ps(R, G));
      Q = _mm256_sqrt_ps(_mm256_mul_ps(R, B));
      S = _mm256_sqrt_ps(_mm256_mul_ps(G, B));
    } else {
      P = signed_sqrt8(_mm256_mul_ps(R, G));
      Q = signed_sqrt8(_mm256_mul_ps(R, B));
      S = signed_sqrt8(_mm256_mul_ps(G, B));
    }
    __m256 o[3];
    for (int c = 0; c < 3; ++c) {
      __m256 v = _mm256_mul_ps(k[c][0], R);
      v = _mm256_fmadd_ps(k[c][1], G, v);
      v = _mm256_fmadd_ps(k[c][2], B, v);
      v = _mm256_fmadd_ps(k[c][3], P, v);
      v = _mm256_fmadd_ps(k[c][4], Q, v);
      o[c] = _mm256_fmadd_ps(k[c][5], S, v);
    }
    simd4::store_xyz(out + 3 * i, _mm256_castps256_ps128(o[0]), _mm256_castps256_ps128(o[1]),
                     _mm256_castps256_ps128(o[2]));
    simd4::store_xyz(out + 3 * i + 12, _mm256_extractf128_ps(o[0], 1), _mm256_extractf128_ps(o[1], 1),
                     _mm256_extractf128_ps(o[2], 1));
  }
  return m;
}

// AVX-512 variants: 16 pixels per step, the deinterleave and interleave as two two-source lane
// permutes per vector (instead of the AVX2 path's 4-lane shuffles, inserts and extracts, which
// bound its speed). The root-polynomial does the AVX2 path's arithmetic lane for lane, the affine
// model the 4-lane kernel's adds and multiplies (identical floats in both cases).
__attribute__((target("avx512f"))) inline __m512 signed_sqrt16(__m512 p) {
  // (maskz with every lane set: the plain sqrt/andnot intrinsics trip GCC 12's -Wmaybe-uninitialized)
  const __m512i sign = _mm512_set1_epi32(static_cast<int>(0x80000000u)), bits = _mm512_castps_si512(p);
  const __m512i magnitude = _mm512_and_si512(bits, _mm512_set1_epi32(0x7fffffff));
  const __m512 r = _mm512_maskz_sqrt_ps(static_cast<__mmask16>(0xffff), _mm512_castsi512_ps(magnitude));
  return _mm512_castsi512_ps(_mm512_or_si512(_mm512_castps_si512(r), _mm512_and_si512(sign, bits)));
}
// Outputs at least this large are written with non-temporal stores by the AVX-512 kernels.
constexpr size_t kStreamBytes = size_t(32) << 20;
// The FMA kernels' formula for one pixel at a time (the same operations lane for lane).
void scalar_root2_fma(const float* in, size_t n, float* out, const float (&a)[3][6]) {
  for (size_t i = 0; i < n; ++i) {
    const float R = in[3 * i], G = in[3 * i + 1], B = in[3 * i + 2];
    const float P = signed_sqrt1(R * G), Q = signed_sqrt1(R * B), S = signed_sqrt1(G * B);
    for (int c = 0; c < 3; ++c) {
      float t = a[c][0] * R;
      t = std::fma(a[c][1], G, t);
      t = std::fma(a[c][2], B, t);
      t = std::fma(a[c][3], P, t);
      t = std::fma(a[c][4], Q, t);
      out[3 * i + c] = std::fma(a[c][5], S, t);
    }
  }
}
// Each coefficient a[c][j] in all 16 lanes.
template <int kTerms>
struct Coefficients16 {
  __m512 k[3][kTerms];
  __attribute__((target("avx512f"))) explicit Coefficients16(const float (&a)[3][kTerms]) {
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < kTerms; ++j) k[c][j] = _mm512_set1_ps(a[c][j]);
  }
};
// The pixel formulas of the AVX-512 loop: X, Y, Z of 16 pixels from their R, G, B.
struct Root2x16 : Coefficients16<6> {
  using Coefficients16::Coefficients16;
  __attribute__((target("avx512f"))) void operator()(__m512 R, __m512 G, __m512 B, __m512 (&o)[3]) const {
    const __m512 P = signed_sqrt16(_mm512_mul_ps(R, G)), Q = signed_sqrt16(_mm512_mul_ps(R, B)),
                 S = signed_sqrt16(_mm512_mul_ps(G, B));
    for (int c = 0; c < 3; ++c) {  // the AVX2 path's order
      __m512 t = _mm512_mul_ps(k[c][0], R);
      t = _mm512_fmadd_ps(k[c][1], G, t);
      t = _mm512_fmadd_ps(k[c][2], B, t);
      t = _mm512_fmadd_ps(k[c][3], P, t);
      t = _mm512_fmadd_ps(k[c][4], Q, t);
      o[c] = _mm512_fmadd_ps(k[c][5], S, t);
    }
  }
};
struct Affinex16 : Coefficients16<4> {
  using Coefficients16::Coefficients16;
  __attribute__((target("avx512f"))) void operator()(__m512 R, __m512 G, __m512 B, __m512 (&o)[3]) const {
    for (int c = 0; c < 3; ++c)  // the 4-lane kernel's association, no fused multiply-add
      o[c] = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(k[c][0], R), _mm512_mul_ps(k[c][1], G)),
                           _mm512_add_ps(_mm512_mul_ps(k[c][2], B), k[c][3]));
  }
};
// Pixels [i0, i1) of the 16-pixel loop (i1 - i0 a multiple of 16); with kStream, non-temporal
// stores, which need out + 3 * i0 64-byte aligned (16 pixels = 192 bytes keep it so).
template <bool kStream, class Formula>
__attribute__((target("avx512f"))) void avx512_steps(const float* in, size_t i0, size_t i1,
                                                     float* out, const Formula& formula) {
  // 16 pixels = 48 floats in three vectors u, v, w. Channel c of pixel l is element 3l + c: the
  // first permute takes elements 0..31 from (u, v), the second the rest from w (its 16..31).
  const __m512i r1 = _mm512_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0);
  const __m512i r2 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29);
  const __m512i g1 = _mm512_setr_epi32(1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0);
  const __m512i g2 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30);
  const __m512i b1 = _mm512_setr_epi32(2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0);
  const __m512i b2 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31);
  // Output vector q holds elements 16q..16q+15: X and Y lanes from (X, Y), then Z lanes from Z.
  const __m512i xy[3] = {_mm512_setr_epi32(0, 16, 0, 1, 17, 0, 2, 18, 0, 3, 19, 0, 4, 20, 0, 5),
                         _mm512_setr_epi32(21, 0, 6, 22, 0, 7, 23, 0, 8, 24, 0, 9, 25, 0, 10, 26),
                         _mm512_setr_epi32(0, 11, 27, 0, 12, 28, 0, 13, 29, 0, 14, 30, 0, 15, 31, 0)};
  const __m512i z[3] = {_mm512_setr_epi32(0, 1, 16, 3, 4, 17, 6, 7, 18, 9, 10, 19, 12, 13, 20, 15),
                        _mm512_setr_epi32(0, 21, 2, 3, 22, 5, 6, 23, 8, 9, 24, 11, 12, 25, 14, 15),
                        _mm512_setr_epi32(26, 1, 2, 27, 4, 5, 28, 7, 8, 29, 10, 11, 30, 13, 14, 31)};
  for (size_t i = i0; i < i1; i += 16) {
    const float* p = in + 3 * i;
    for (int q = 0; q < 3; ++q) simd4::prefetch_ahead(p + 16 * q);  // the three lines 192 bytes take
    const __m512 u = _mm512_loadu_ps(p), v = _mm512_loadu_ps(p + 16), w = _mm512_loadu_ps(p + 32);
    const __m512 R = _mm512_permutex2var_ps(_mm512_permutex2var_ps(u, r1, v), r2, w);
    const __m512 G = _mm512_permutex2var_ps(_mm512_permutex2var_ps(u, g1, v), g2, w);
    const __m512 B = _mm512_permutex2var_ps(_mm512_permutex2var_ps(u, b1, v), b2, w);
    __m512 o[3];
    formula(R, G, B, o);
    float* d = out + 3 * i;
    for (int q = 0; q < 3; ++q) {
      const __m512 v3 = _mm512_permutex2var_ps(_mm512_permutex2var_ps(o[0], xy[q], o[1]), z[q], o[2]);
      if constexpr (kStream) _mm512_stream_ps(d + 16 * q, v3);
      else _mm512_storeu_ps(d + 16 * q, v3);
    }
  }
  if constexpr (kStream) _mm_sfence();  // the streamed lines are ordered before later stores
}
// Runs the 16-pixel loop over n pixels and returns how many leading pixels it wrote: n rounded
// down to 16, or, for a large output (≥ kStreamBytes, past any cache), to `boundary` pixels
// (where the next narrower kernel alone would stop). A large output goes out with 64-byte
// non-temporal stores — whole cache lines written without being read first, as glibc's memcpy
// writes at this size; the pixels before the first 64-byte aligned output and after the last
// 16-pixel step up to the boundary go through `one_by_one` (the same formula: identical floats).
template <class Formula, class Coefficients>
__attribute__((target("avx512f"))) size_t avx512_apply(const float* in, size_t n, float* out,
                                                        const Coefficients& a, size_t boundary,
                                                        void (*one_by_one)(const float*, size_t, float*, const Coefficients&)) {
  const Formula formula(a);
  if (n * 3 * sizeof(float) >= kStreamBytes) {
    // out + 3·start is 64-byte aligned for one start in 0..15 (12·start covers every multiple of 4
    // modulo 64, and a float* is 4-byte aligned).
    size_t start = 0;
    while ((reinterpret_cast<std::uintptr_t>(out + 3 * start) & 63) != 0) ++start;
    const size_t nb = n - n % boundary, end = start + ((nb - start) & ~size_t(15));
    one_by_one(in, start, out, a);
    avx512_steps<true>(in, start, end, out, formula);
    one_by_one(in + 3 * end, nb - end, out + 3 * end, a);
    return nb;
  }
  const size_t m = n & ~size_t(15);
  avx512_steps<false>(in, 0, m, out, formula);
  return m;
}
// The root-polynomial stops at the AVX2 kernel's 8-pixel boundary (its tail is the AVX2 path's,
// exactly as when AVX2 does the whole image); the affine model needs none (every path gives the
// scalar formula's floats), so its large outputs are done here to the last pixel.
__attribute__((target("avx512f"))) size_t avx512_root2(const float* in, size_t n,
                                                        float* out, const float (&a)[3][6]) {
  return avx512_apply<Root2x16>(in, n, out, a, 8, scalar_root2_fma);
}
__attribute__((target("avx512f"))) size_t avx512_affine(const float* in, size_t n,
                                                         float* out, const float (&a)[3][4]) {
  return avx512_apply<Affinex16>(in, n, out, a, 1, scalar_affine);
}

// The widest kernels the CPU (and the limit set for tests and benchmarks) allows: 0 = 4-lane
// SSE2, 1 = AVX2+FMA, 2 = AVX-512.
int g_kernel_limit = 2;
int cpu_kernel_level() {
  static const int level = __builtin_cpu_supports("avx512f") ? 2
                           : __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? 1
                                                                                             : 0;
  return std::min(level, g_kernel_limit);
}
#endif
#endif  // TRISTIM_SIMD4

// The vector part of each model: how many leading pixels it wrote (0 without SIMD).
size_t vector_affine(const float* in, size_t n, float* out, const float (&a)[3][4]) {
#ifdef TRISTIM_SIMD4
  size_t done = 0;
#ifdef TRISTIM_HAVE_AVX2_PATH
  if (cpu_kernel_level() >= 2) done = avx512_affine(in, n, out, a);
#endif
  return done + simd_affine(in + 3 * done, n - done, out + 3 * done, a);
#else
  (void)in, (void)n, (void)out, (void)a;
  return 0;
#endif
}
size_t vector_root2(const float* in, size_t n, float* out, const float (&a)[3][6]) {
#ifdef TRISTIM_SIMD4
  size_t done = 0;
#ifdef TRISTIM_HAVE_AVX2_PATH
  // Widest first; each narrower kernel takes the pixels left over (the pixels an AVX-512 step
  // leaves go through the AVX2 path, exactly as when AVX2 does the whole image).
  const int level = cpu_kernel_level();
  if (level >= 2) done += avx512_root2(in, n, out, a);
  if (level >= 1) done += avx2_root2(in + 3 * done, n - done, out + 3 * done, a);
#endif
  return done + simd_root2(in + 3 * done, n - done, out + 3 * done, a);
#else
  (void)in, (void)n, (void)out, (void)a;
  return 0;
#endif
}

}  // namespace

int set_image_kernel_limit(int level) {
#ifdef TRISTIM_HAVE_AVX2_PATH
  const int previous = g_kernel_limit;
  g_kernel_limit = std::max(0, std::min(2, level));
  return previous;
#else
  (void)level;
  return 0;
#endif
}

void apply_to_image(const Model& model, const float* rgb, size_t n_pixels, float* xyz) {
  const ModelInfo& info = model_info(model.id);
  check_coefficient_shape(model, info);
  if (n_pixels == 0) return;
  if (rgb == nullptr || xyz == nullptr)
    throw Error(ErrorCode::InvalidArgument, "apply_to_image: null image buffer");
  const auto at = [](const float* p) { return reinterpret_cast<std::uintptr_t>(p); };
  if (xyz != rgb && at(xyz) < at(rgb + 3 * n_pixels) && at(rgb) < at(xyz + 3 * n_pixels))
    throw Error(ErrorCode::InvalidArgument, "apply_to_image: the output overlaps the input without being it "
                                            "(give the same buffer to apply in place, or two separate ones)");
  const Eigen::MatrixXd& C = model.coefficients;
  float k[3][kMaxModelTerms];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < info.n_terms; ++j) k[c][j] = static_cast<float>(C(c, j));

  const bool is_linear = info.linear;
  const bool is_affine = info.n_terms == 4 && info.terms[3].r + info.terms[3].g + info.terms[3].b == 0 &&
                         info.terms[0].r == 1 && info.terms[1].g == 1 && info.terms[2].b == 1;
  const bool is_root2 = info.root && info.n_terms == 6 && info.terms[0].r == 1 && info.terms[1].g == 1 &&
                        info.terms[2].b == 1;
  if (is_linear || is_affine) {
    float a[3][4];
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < 3; ++j) a[c][j] = k[c][j];
      a[c][3] = is_affine ? k[c][3] : 0.f;
    }
    const size_t done = vector_affine(rgb, n_pixels, xyz, a);
    scalar_affine(rgb + 3 * done, n_pixels - done, xyz + 3 * done, a);
    return;
  }
  if (is_root2) {
    // Terms 3..5 are sqrt of the product of two channels; reorder to (RG, RB, GB).
    float a[3][6];
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < 3; ++j) a[c][j] = k[c][j];
    for (int j = 3; j < 6; ++j) {
      const Monomial& t = info.terms[j];
      const int slot = t.r && t.g ? 3 : (t.r && t.b ? 4 : 5);
      for (int c = 0; c < 3; ++c) a[c][slot] = k[c][j];
    }
    const size_t done = vector_root2(rgb, n_pixels, xyz, a);
    scalar_root2(rgb + 3 * done, n_pixels - done, xyz + 3 * done, a);
    return;
  }
  // Generic path: double expansion per pixel on the stack.
  double phi[kMaxModelTerms];
  for (size_t i = 0; i < n_pixels; ++i) {
    expand(info, rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], phi);
    for (int c = 0; c < 3; ++c) {
      double s = 0;
      for (int j = 0; j < info.n_terms; ++j) s += C(c, j) * phi[j];
      xyz[3 * i + c] = static_cast<float>(s);
    }
  }
}

}  // namespace tristim

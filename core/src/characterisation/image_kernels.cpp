// Whole-image application of a model (apply_to_image): 4-lane kernels (SSE2 natively, SIMD128
// in wasm; simd4.hpp) and an AVX2+FMA variant for the 3×3, affine and degree-2 root-polynomial
// models, scalar loops with the same association for the tails, a generic double path for the rest.
// Without FMA the kernels and the scalar loops give bit-identical results (native SSE2 and wasm
// alike); the AVX2 path differs by FMA rounding (tests/core/characterisation/image_kernels_test).
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
void scalar_affine(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][4]) {
  for (size_t i = 0; i < n; ++i) {
    const float R = in[3 * i], G = in[3 * i + 1], B = in[3 * i + 2];
    for (int c = 0; c < 3; ++c) out[3 * i + c] = (a[c][0] * R + a[c][1] * G) + (a[c][2] * B + a[c][3]);
  }
}
void scalar_root2(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][6]) {
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
template <bool kStream>
size_t simd_affine_t(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][4]) {
  using namespace simd4;
  f4 k[3][4];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 4; ++j) k[c][j] = splat(a[c][j]);
  const size_t m = n & ~size_t(3);
  for (size_t i = 0; i < m; i += 4) {
    f4 R, G, B;
    load_rgb(in + 3 * i, R, G, B);
    f4 o[3];
    for (int c = 0; c < 3; ++c) o[c] = add(add(mul(k[c][0], R), mul(k[c][1], G)), add(mul(k[c][2], B), k[c][3]));
    store_xyz<kStream>(out + 3 * i, o[0], o[1], o[2]);
  }
  if (kStream) stream_fence();
  return m;
}

template <bool kStream>
size_t simd_root2_t(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][6]) {
  using namespace simd4;
  f4 k[3][6];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 6; ++j) k[c][j] = splat(a[c][j]);
  const size_t m = n & ~size_t(3);
  for (size_t i = 0; i < m; i += 4) {
    f4 R, G, B;
    load_rgb(in + 3 * i, R, G, B);
    const f4 P = signed_sqrt(mul(R, G)), Q = signed_sqrt(mul(R, B)), S = signed_sqrt(mul(G, B));
    f4 o[3];
    for (int c = 0; c < 3; ++c)
      o[c] = add(add(add(mul(k[c][0], R), mul(k[c][1], G)), add(mul(k[c][2], B), mul(k[c][3], P))),
                 add(mul(k[c][4], Q), mul(k[c][5], S)));
    store_xyz<kStream>(out + 3 * i, o[0], o[1], o[2]);
  }
  if (kStream) stream_fence();
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
template <bool kStream>
__attribute__((target("avx2,fma"))) size_t avx2_root2_t(const float* __restrict in, size_t n,
                                                        float* __restrict out, const float (&a)[3][6]) {
  __m256 k[3][6];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 6; ++j) k[c][j] = _mm256_set1_ps(a[c][j]);
  const size_t m = n & ~size_t(7);
  for (size_t i = 0; i < m; i += 8) {
    __m128 R0, G0, B0, R1, G1, B1;
    simd4::load_rgb(in + 3 * i, R0, G0, B0);
    simd4::load_rgb(in + 3 * i + 12, R1, G1, B1);
    const __m256 R = join8(R0, R1), G = join8(G0, G1), B = join8(B0, B1);
    const __m256 P = signed_sqrt8(_mm256_mul_ps(R, G)), Q = signed_sqrt8(_mm256_mul_ps(R, B)),
                 S = signed_sqrt8(_mm256_mul_ps(G, B));
    __m256 o[3];
    for (int c = 0; c < 3; ++c) {
      __m256 v = _mm256_mul_ps(k[c][0], R);
      v = _mm256_fmadd_ps(k[c][1], G, v);
      v = _mm256_fmadd_ps(k[c][2], B, v);
      v = _mm256_fmadd_ps(k[c][3], P, v);
      v = _mm256_fmadd_ps(k[c][4], Q, v);
      o[c] = _mm256_fmadd_ps(k[c][5], S, v);
    }
    simd4::store_xyz<kStream>(out + 3 * i, _mm256_castps256_ps128(o[0]), _mm256_castps256_ps128(o[1]),
                              _mm256_castps256_ps128(o[2]));
    simd4::store_xyz<kStream>(out + 3 * i + 12, _mm256_extractf128_ps(o[0], 1), _mm256_extractf128_ps(o[1], 1),
                              _mm256_extractf128_ps(o[2], 1));
  }
  if (kStream) _mm_sfence();
  return m;
}
bool cpu_has_avx2_fma() {
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
}
#endif

// Streaming stores for images larger than the caches (and a 16-byte aligned output).
inline bool use_stream(const float* out, size_t n) {
  return simd4::kHasStream && n >= (size_t(1) << 20) && reinterpret_cast<uintptr_t>(out) % 16 == 0;
}
#endif  // TRISTIM_SIMD4

// The vector part of each model: how many leading pixels it wrote (0 without SIMD).
size_t vector_affine(const float* in, size_t n, float* out, const float (&a)[3][4]) {
#ifdef TRISTIM_SIMD4
  return use_stream(out, n) ? simd_affine_t<true>(in, n, out, a) : simd_affine_t<false>(in, n, out, a);
#else
  (void)in, (void)n, (void)out, (void)a;
  return 0;
#endif
}
size_t vector_root2(const float* in, size_t n, float* out, const float (&a)[3][6]) {
#ifdef TRISTIM_SIMD4
  const bool stream = use_stream(out, n);
#ifdef TRISTIM_HAVE_AVX2_PATH
  if (cpu_has_avx2_fma()) {
    const size_t done = stream ? avx2_root2_t<true>(in, n, out, a) : avx2_root2_t<false>(in, n, out, a);
    const size_t rest = stream ? simd_root2_t<true>(in + 3 * done, n - done, out + 3 * done, a)
                               : simd_root2_t<false>(in + 3 * done, n - done, out + 3 * done, a);
    return done + rest;
  }
#endif
  return stream ? simd_root2_t<true>(in, n, out, a) : simd_root2_t<false>(in, n, out, a);
#else
  (void)in, (void)n, (void)out, (void)a;
  return 0;
#endif
}

}  // namespace

void apply_to_image(const Model& model, const float* rgb, size_t n_pixels, float* xyz) {
  const ModelInfo& info = model_info(model.id);
  check_coefficient_shape(model, info);
  if (n_pixels == 0) return;
  if (rgb == nullptr || xyz == nullptr)
    throw Error(ErrorCode::InvalidArgument, "apply_to_image: null image buffer");
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

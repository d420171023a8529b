// Whole-image application of a model (apply_to_image): planar blocks, SSE/AVX2 kernels for the
// 3×3, affine and degree-2 root-polynomial models, a generic double path for the rest.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "tristim/characterisation/models.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

// Block size of the image loops: deinterleave into planar float arrays the compiler vectorises.
constexpr size_t kBlock = 512;

// Interleaved RGB -> planar r, g, b (and planar x, y, z -> interleaved), 4 pixels per step
// with SSE shuffles where available.
inline void deinterleave(const float* __restrict in, float* __restrict r, float* __restrict g,
                         float* __restrict b, size_t m) {
  size_t i = 0;
#if defined(__SSE2__)
  for (; i + 4 <= m; i += 4) {
    const __m128 a = _mm_loadu_ps(in + 3 * i), bb = _mm_loadu_ps(in + 3 * i + 4), c = _mm_loadu_ps(in + 3 * i + 8);
    const __m128 t0 = _mm_shuffle_ps(a, bb, _MM_SHUFFLE(1, 0, 2, 1));  // g0 b0 g1 b1
    const __m128 t1 = _mm_shuffle_ps(bb, c, _MM_SHUFFLE(2, 1, 3, 2));  // r2 g2 r3 g3
    _mm_store_ps(r + i, _mm_shuffle_ps(a, t1, _MM_SHUFFLE(2, 0, 3, 0)));
    _mm_store_ps(g + i, _mm_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 1, 2, 0)));
    _mm_store_ps(b + i, _mm_shuffle_ps(t0, c, _MM_SHUFFLE(3, 0, 3, 1)));
  }
#endif
  for (; i < m; ++i) {
    r[i] = in[3 * i];
    g[i] = in[3 * i + 1];
    b[i] = in[3 * i + 2];
  }
}

inline void interleave(const float* __restrict x, const float* __restrict y, const float* __restrict z,
                       float* __restrict out, size_t m) {
  size_t i = 0;
#if defined(__SSE2__)
  for (; i + 4 <= m; i += 4) {
    const __m128 X = _mm_load_ps(x + i), Y = _mm_load_ps(y + i), Z = _mm_load_ps(z + i);
    const __m128 lo = _mm_unpacklo_ps(X, Y), hi = _mm_unpackhi_ps(X, Y);  // x0 y0 x1 y1 | x2 y2 x3 y3
    const __m128 a = _mm_shuffle_ps(Z, lo, _MM_SHUFFLE(2, 2, 0, 0));     // z0 z0 x1 x1
    const __m128 b = _mm_shuffle_ps(lo, Z, _MM_SHUFFLE(1, 1, 3, 3));     // y1 y1 z1 z1
    const __m128 c = _mm_shuffle_ps(Z, hi, _MM_SHUFFLE(2, 2, 2, 2));     // z2 z2 x3 x3
    const __m128 d = _mm_shuffle_ps(hi, Z, _MM_SHUFFLE(3, 3, 3, 3));     // y3 y3 z3 z3
    _mm_storeu_ps(out + 3 * i, _mm_shuffle_ps(lo, a, _MM_SHUFFLE(2, 0, 1, 0)));
    _mm_storeu_ps(out + 3 * i + 4, _mm_shuffle_ps(b, hi, _MM_SHUFFLE(1, 0, 2, 0)));
    _mm_storeu_ps(out + 3 * i + 8, _mm_shuffle_ps(c, d, _MM_SHUFFLE(2, 0, 2, 0)));
  }
#endif
  for (; i < m; ++i) {
    out[3 * i] = x[i];
    out[3 * i + 1] = y[i];
    out[3 * i + 2] = z[i];
  }
}

template <class Kernel>
void image_blocks(const float* rgb, size_t n, float* xyz, Kernel&& kernel) {
  alignas(64) float r[kBlock], g[kBlock], b[kBlock], x[kBlock], y[kBlock], z[kBlock];
  for (size_t start = 0; start < n; start += kBlock) {
    const size_t m = std::min(kBlock, n - start);
    deinterleave(rgb + 3 * start, r, g, b, m);
    kernel(r, g, b, x, y, z, m);
    interleave(x, y, z, xyz + 3 * start, m);
  }
}

void kernel_affine(const float* __restrict r, const float* __restrict g, const float* __restrict b,
                   float* __restrict x, float* __restrict y, float* __restrict z, size_t m, const float (&a)[3][4]) {
  const float a00 = a[0][0], a01 = a[0][1], a02 = a[0][2], a03 = a[0][3];
  const float a10 = a[1][0], a11 = a[1][1], a12 = a[1][2], a13 = a[1][3];
  const float a20 = a[2][0], a21 = a[2][1], a22 = a[2][2], a23 = a[2][3];
  for (size_t i = 0; i < m; ++i) {
    const float R = r[i], G = g[i], B = b[i];
    x[i] = a00 * R + a01 * G + a02 * B + a03;
    y[i] = a10 * R + a11 * G + a12 * B + a13;
    z[i] = a20 * R + a21 * G + a22 * B + a23;
  }
}

// Degree-2 root-polynomial, coefficient columns (R, G, B, √RG, √RB, √GB), signed roots.
void kernel_root2(const float* __restrict r, const float* __restrict g, const float* __restrict b,
                  float* __restrict x, float* __restrict y, float* __restrict z, size_t m, const float (&a)[3][6]) {
  alignas(64) float s0[kBlock], s1[kBlock], s2[kBlock];
  for (size_t i = 0; i < m; ++i) {
    s0[i] = r[i] * g[i];
    s1[i] = r[i] * b[i];
    s2[i] = g[i] * b[i];
  }
  // Signed square root through Eigen's packet sqrt (std::sqrt keeps errno semantics and
  // stays scalar).
  alignas(64) float t[kBlock];
  for (float* s : {s0, s1, s2}) {
    Eigen::Map<Eigen::ArrayXf, Eigen::Aligned16> v(s, static_cast<Eigen::Index>(m));
    Eigen::Map<Eigen::ArrayXf, Eigen::Aligned16> root(t, static_cast<Eigen::Index>(m));
    root = v.abs().sqrt();
    for (size_t i = 0; i < m; ++i) s[i] = s[i] < 0.f ? -t[i] : t[i];
  }
  const float a00 = a[0][0], a01 = a[0][1], a02 = a[0][2], a03 = a[0][3], a04 = a[0][4], a05 = a[0][5];
  const float a10 = a[1][0], a11 = a[1][1], a12 = a[1][2], a13 = a[1][3], a14 = a[1][4], a15 = a[1][5];
  const float a20 = a[2][0], a21 = a[2][1], a22 = a[2][2], a23 = a[2][3], a24 = a[2][4], a25 = a[2][5];
  for (size_t i = 0; i < m; ++i) {
    const float R = r[i], G = g[i], B = b[i], P = s0[i], Q = s1[i], S = s2[i];
    x[i] = a00 * R + a01 * G + a02 * B + a03 * P + a04 * Q + a05 * S;
    y[i] = a10 * R + a11 * G + a12 * B + a13 * P + a14 * Q + a15 * S;
    z[i] = a20 * R + a21 * G + a22 * B + a23 * P + a24 * Q + a25 * S;
  }
}

#if defined(__SSE2__)
// Fused SSE loops, 4 pixels per step straight from and to the interleaved buffers; return how
// many pixels they handled (a multiple of 4); the caller finishes the tail.
inline void load4(const float* in, __m128& R, __m128& G, __m128& B) {
  const __m128 a = _mm_loadu_ps(in), b = _mm_loadu_ps(in + 4), c = _mm_loadu_ps(in + 8);
  const __m128 t0 = _mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 0, 2, 1));
  const __m128 t1 = _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 1, 3, 2));
  R = _mm_shuffle_ps(a, t1, _MM_SHUFFLE(2, 0, 3, 0));
  G = _mm_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 1, 2, 0));
  B = _mm_shuffle_ps(t0, c, _MM_SHUFFLE(3, 0, 3, 1));
}
template <bool kStream>
inline void put(float* out, __m128 v) {
  if (kStream) _mm_stream_ps(out, v);  // non-temporal: no read-for-ownership of the output
  else _mm_storeu_ps(out, v);
}
template <bool kStream>
inline void store4(float* out, __m128 X, __m128 Y, __m128 Z) {
  const __m128 lo = _mm_unpacklo_ps(X, Y), hi = _mm_unpackhi_ps(X, Y);
  const __m128 a = _mm_shuffle_ps(Z, lo, _MM_SHUFFLE(2, 2, 0, 0));
  const __m128 b = _mm_shuffle_ps(lo, Z, _MM_SHUFFLE(1, 1, 3, 3));
  const __m128 c = _mm_shuffle_ps(Z, hi, _MM_SHUFFLE(2, 2, 2, 2));
  const __m128 d = _mm_shuffle_ps(hi, Z, _MM_SHUFFLE(3, 3, 3, 3));
  put<kStream>(out, _mm_shuffle_ps(lo, a, _MM_SHUFFLE(2, 0, 1, 0)));
  put<kStream>(out + 4, _mm_shuffle_ps(b, hi, _MM_SHUFFLE(1, 0, 2, 0)));
  put<kStream>(out + 8, _mm_shuffle_ps(c, d, _MM_SHUFFLE(2, 0, 2, 0)));
}
inline __m128 signed_sqrt4(__m128 p) {
  const __m128 sign = _mm_set1_ps(-0.0f);
  return _mm_or_ps(_mm_sqrt_ps(_mm_andnot_ps(sign, p)), _mm_and_ps(sign, p));
}

template <bool kStream>
size_t sse_affine_t(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][4]) {
  __m128 k[3][4];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 4; ++j) k[c][j] = _mm_set1_ps(a[c][j]);
  const size_t m = n & ~size_t(3);
  for (size_t i = 0; i < m; i += 4) {
    __m128 R, G, B;
    load4(in + 3 * i, R, G, B);
    __m128 o[3];
    for (int c = 0; c < 3; ++c)
      o[c] = _mm_add_ps(_mm_add_ps(_mm_mul_ps(k[c][0], R), _mm_mul_ps(k[c][1], G)),
                        _mm_add_ps(_mm_mul_ps(k[c][2], B), k[c][3]));
    store4<kStream>(out + 3 * i, o[0], o[1], o[2]);
  }
  if (kStream) _mm_sfence();
  return m;
}

template <bool kStream>
size_t sse_root2_t(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][6]) {
  __m128 k[3][6];
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < 6; ++j) k[c][j] = _mm_set1_ps(a[c][j]);
  const size_t m = n & ~size_t(3);
  for (size_t i = 0; i < m; i += 4) {
    __m128 R, G, B;
    load4(in + 3 * i, R, G, B);
    const __m128 P = signed_sqrt4(_mm_mul_ps(R, G)), Q = signed_sqrt4(_mm_mul_ps(R, B)),
                 S = signed_sqrt4(_mm_mul_ps(G, B));
    __m128 o[3];
    for (int c = 0; c < 3; ++c)
      o[c] = _mm_add_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(k[c][0], R), _mm_mul_ps(k[c][1], G)),
                                   _mm_add_ps(_mm_mul_ps(k[c][2], B), _mm_mul_ps(k[c][3], P))),
                        _mm_add_ps(_mm_mul_ps(k[c][4], Q), _mm_mul_ps(k[c][5], S)));
    store4<kStream>(out + 3 * i, o[0], o[1], o[2]);
  }
  if (kStream) _mm_sfence();
  return m;
}
#endif

#if !defined(__SSE2__)
// Without SSE (wasm): one fused pass over the interleaved buffers, no block copies.
inline float signed_sqrt1(float p) {
  const float r = std::sqrt(p < 0.f ? -p : p);
  return p < 0.f ? -r : r;
}
size_t scalar_affine(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][4]) {
  const float a00 = a[0][0], a01 = a[0][1], a02 = a[0][2], a03 = a[0][3];
  const float a10 = a[1][0], a11 = a[1][1], a12 = a[1][2], a13 = a[1][3];
  const float a20 = a[2][0], a21 = a[2][1], a22 = a[2][2], a23 = a[2][3];
  for (size_t i = 0; i < n; ++i) {
    const float R = in[3 * i], G = in[3 * i + 1], B = in[3 * i + 2];
    out[3 * i] = a00 * R + a01 * G + a02 * B + a03;
    out[3 * i + 1] = a10 * R + a11 * G + a12 * B + a13;
    out[3 * i + 2] = a20 * R + a21 * G + a22 * B + a23;
  }
  return n;
}
size_t scalar_root2(const float* __restrict in, size_t n, float* __restrict out, const float (&a)[3][6]) {
  const float a00 = a[0][0], a01 = a[0][1], a02 = a[0][2], a03 = a[0][3], a04 = a[0][4], a05 = a[0][5];
  const float a10 = a[1][0], a11 = a[1][1], a12 = a[1][2], a13 = a[1][3], a14 = a[1][4], a15 = a[1][5];
  const float a20 = a[2][0], a21 = a[2][1], a22 = a[2][2], a23 = a[2][3], a24 = a[2][4], a25 = a[2][5];
  for (size_t i = 0; i < n; ++i) {
    const float R = in[3 * i], G = in[3 * i + 1], B = in[3 * i + 2];
    const float P = signed_sqrt1(R * G), Q = signed_sqrt1(R * B), S = signed_sqrt1(G * B);
    out[3 * i] = a00 * R + a01 * G + a02 * B + a03 * P + a04 * Q + a05 * S;
    out[3 * i + 1] = a10 * R + a11 * G + a12 * B + a13 * P + a14 * Q + a15 * S;
    out[3 * i + 2] = a20 * R + a21 * G + a22 * B + a23 * P + a24 * Q + a25 * S;
  }
  return n;
}
#endif

#if defined(__SSE2__)
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
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
    load4(in + 3 * i, R0, G0, B0);
    load4(in + 3 * i + 12, R1, G1, B1);
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
    store4<kStream>(out + 3 * i, _mm256_castps256_ps128(o[0]), _mm256_castps256_ps128(o[1]),
                    _mm256_castps256_ps128(o[2]));
    store4<kStream>(out + 3 * i + 12, _mm256_extractf128_ps(o[0], 1), _mm256_extractf128_ps(o[1], 1),
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
  return n >= (size_t(1) << 20) && reinterpret_cast<uintptr_t>(out) % 16 == 0;
}
size_t sse_affine(const float* in, size_t n, float* out, const float (&a)[3][4]) {
  return use_stream(out, n) ? sse_affine_t<true>(in, n, out, a) : sse_affine_t<false>(in, n, out, a);
}
size_t sse_root2(const float* in, size_t n, float* out, const float (&a)[3][6]) {
  const bool stream = use_stream(out, n);
#ifdef TRISTIM_HAVE_AVX2_PATH
  if (cpu_has_avx2_fma()) {
    const size_t done = stream ? avx2_root2_t<true>(in, n, out, a) : avx2_root2_t<false>(in, n, out, a);
    const size_t rest = stream ? sse_root2_t<true>(in + 3 * done, n - done, out + 3 * done, a)
                               : sse_root2_t<false>(in + 3 * done, n - done, out + 3 * done, a);
    return done + rest;
  }
#endif
  return stream ? sse_root2_t<true>(in, n, out, a) : sse_root2_t<false>(in, n, out, a);
}
#endif

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
#if defined(__SSE2__)
    const size_t done = sse_affine(rgb, n_pixels, xyz, a);
#else
    const size_t done = scalar_affine(rgb, n_pixels, xyz, a);
#endif
    image_blocks(rgb + 3 * done, n_pixels - done, xyz + 3 * done,
                 [&a](const float* r, const float* g, const float* b, float* x, float* y, float* z, size_t m) {
                   kernel_affine(r, g, b, x, y, z, m, a);
                 });
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
#if defined(__SSE2__)
    const size_t done = sse_root2(rgb, n_pixels, xyz, a);
#else
    const size_t done = scalar_root2(rgb, n_pixels, xyz, a);
#endif
    image_blocks(rgb + 3 * done, n_pixels - done, xyz + 3 * done,
                 [&a](const float* r, const float* g, const float* b, float* x, float* y, float* z, size_t m) {
                   kernel_root2(r, g, b, x, y, z, m, a);
                 });
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

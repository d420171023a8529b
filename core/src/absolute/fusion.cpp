// Guarnera 2018 section 3.1: Algorithm 1 and the weighted multi-exposure fusion
// (rules in tristim/absolute/fusion.hpp).
#include "tristim/absolute/fusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "../citations.hpp"
#include "../detmath.hpp"
#include "../large_buffer.hpp"
#include "../simd4.hpp"
#include "tristim/error.hpp"

namespace tristim {

const char* fusion_mode_id(FusionMode mode) { return mode == FusionMode::Recursive ? "recursive" : "weighted"; }

FusionMode fusion_mode_from_id(const std::string& id) {
  if (id == "weighted" || id == "fusion") return FusionMode::Weighted;
  if (id == "recursive" || id == "algorithm1" || id == "select") return FusionMode::Recursive;
  throw Error(ErrorCode::UnknownId, "unknown exposure combination '" + id + "' (weighted, recursive)");
}

std::vector<FusionModeInfo> fusion_mode_table() {
  const std::string guarnera = citation::kGuarnera2018;
  return {
      {fusion_mode_id(FusionMode::Weighted), "weighted (every reliable exposure)",
       guarnera + ", section 3.1 (zones Z_u, Z_c, Z_o); weighting by reliability and t/N²",
       "every unsaturated exposure contributes, weighted by the reliability of its zone and its exposure"},
      {fusion_mode_id(FusionMode::Recursive), "Algorithm 1 (recursive selection)", guarnera + ", Algorithm 1",
       "per pixel and channel, one exposure: from the middle one, the next longer in Z_u, the next shorter in Z_o"},
  };
}

double reliability_Guarnera2018(Zone zone, double u, double w, double u_min) {
  if (zone != Zone::Saturated && u <= u_min) return 0;
  switch (zone) {
    case Zone::Saturated: return 0;
    case Zone::Centre: return 1;
    case Zone::Under: return u > 0 ? std::min(1.0, w * u) : 0.0;
    case Zone::Over: return std::max(0.0, std::min(1.0, w * (1 - u)));
  }
  return 0;
}

namespace {

// x^p on [0, x_max] by linear interpolation in a table of 65536 segments (relative error below
// 1e-5 for x > 1e-3·x_max with p near 1); the power itself outside. Signed: (−x)^p = −x^p.
// detmath's pow, not the C library's: the same table and values natively and in wasm (its ~50 ns
// a call is ~3 ms a table; FusionTables builds three per bracket).
class PowerTable {
 public:
  PowerTable() = default;
  PowerTable(double p, double x_max) : p_(p), linear_(p == 1.0), x_max_(x_max), scale_(kN / x_max) {
    if (linear_) return;
    table_.resize(kN + 2);
    for (int i = 0; i <= kN + 1; ++i) table_[i] = static_cast<float>(detmath::pow(i / scale_, p));
  }
  bool linear() const { return linear_; }
  /// The same lookup in float (the fusion's pixel loop); x ≥ 0 or < 0 alike.
  float at(float x) const {
    const float a = std::fabs(x);
    float y;
    if (a < static_cast<float>(x_max_)) {
      const float t = a * static_cast<float>(scale_);
      const int i = static_cast<int>(t);
      const float f = t - static_cast<float>(i);
      y = table_[i] + f * (table_[i + 1] - table_[i]);
    } else {
      y = static_cast<float>(detmath::pow(static_cast<double>(a), p_));
    }
    return x < 0 ? -y : y;
  }
  double operator()(double x) const {
    if (linear_) return x;
    const double a = std::fabs(x);
    double y;
    if (a < x_max_) {
      const double t = a * scale_;
      const int i = static_cast<int>(t);
      const double f = t - i;
      y = table_[i] + f * (table_[i + 1] - table_[i]);
    } else {
      y = detmath::pow(a, p_);
    }
    return x < 0 ? -y : y;
  }

 private:
  static constexpr int kN = 65536;
  double p_ = 1;
  bool linear_ = true;
  double x_max_ = 1, scale_ = 1;
  std::vector<float> table_;
};

}  // namespace

namespace detail {
// The roots x^(1/k3) of eq (8) per channel, over the range eq (7) reaches (R' = u·A_G/A_c·f(r)
// up to 1.05 of its largest value): they depend on the normalisation and the curves, not on the
// exposure, so a bracket builds them once, not once per frame (3 × 65538 detmath::pow: ~10 ms
// natively, ~27 ms in wasm).
struct FusionTables {
  PowerTable root[3];
  FusionTables(const Normalisation& n, const LuminanceFit& fit) {
    double f_max = 1;
    if (n.falloff) {  // f(r) over r in [0, 1] (r = 1 at the corners)
      for (int i = 0; i <= 16; ++i) {
        const double r = i / 16.0;
        f_max = std::max(f_max, n.falloff->p1 * r * r + n.falloff->p2 * r + n.falloff->p3);
      }
    }
    for (int c = 0; c < 3; ++c) root[c] = PowerTable(1.0 / fit.curves[c].k3, 1.05 * n.area_ratio(c) * f_max);
  }
};
}  // namespace detail

namespace {

// Eqs (7), (8), (10) for every pixel of one frame, with the per-channel constants hoisted.
struct FrameKernel {
  const Normalisation& n;
  double inv_eps;
  double floor[3], inv_range[3], area[3], inv_k2[3], k1[3], u_min[3];
  const PowerTable* root[3];

  FrameKernel(const Normalisation& norm, const LuminanceFit& fit, const ExposureSettings& e,
              const detail::FusionTables& tables)
      : n(norm), inv_eps(1.0 / e.factor(fit.iso_reference)) {
    for (int c = 0; c < 3; ++c) {
      floor[c] = n.noise_floor[c];
      u_min[c] = n.detection_unit(c);
      inv_range[c] = 1.0 / (n.saturation[c] - n.noise_floor[c]);
      area[c] = n.area_ratio(c);
      inv_k2[c] = 1.0 / fit.curves[c].k2;
      k1[c] = fit.curves[c].k1;
      root[c] = &tables.root[c];
    }
  }
  // L(c) in cd/m² of value v at fall-off f (eqs 7, 8, 10); u is (v − n)/(S − n).
  double luminance(int c, double u, double f) const {
    const double R = u * area[c] * f;                      // eq (7)
    return ((*root[c])(R) * inv_k2[c] - k1[c]) * inv_eps;  // eqs (8), (10)
  }
};

// The weighted fusion's per-frame constants, in float (the pixel loop below is the hot path of a
// bracket: 5 × 24 MP). Same rules as FrameKernel + Normalisation::zone + reliability_Guarnera2018:
//   saturated ⇔ flagged or v ≥ clip (clip: the float nearest above S − max(0.5, 1e-4·(S − n)));
//   h = 0 for u ≤ u_min, else min(1, w·u, w·(1 − u)) — the zones' ramps written without branches
//   (w·u < 1 exactly in Z_u, w·(1 − u) < 1 exactly in Z_o);
//   L = (R'^(1/k3)/k2 − k1)/ε with R' = u·A_G/A_c·f(r)   (eqs 7, 8, 10).
struct FastKernel {
  float floor[3], inv_range[3], clip[3], u_min[3], area[3], gain[3], offset[3];
  float w, eps;
  bool linear[3];
  const PowerTable* root[3];

  FastKernel(const FrameKernel& k, const Normalisation& n, double eps_d) : w(static_cast<float>(n.w)), eps(static_cast<float>(eps_d)) {
    for (int c = 0; c < 3; ++c) {
      floor[c] = static_cast<float>(k.floor[c]);
      inv_range[c] = static_cast<float>(k.inv_range[c]);
      const double range = n.saturation[c] - n.noise_floor[c];
      const double t = n.saturation[c] - std::max(0.5, 1e-4 * range);
      float tf = static_cast<float>(t);
      if (static_cast<double>(tf) < t) tf = std::nextafter(tf, std::numeric_limits<float>::infinity());
      clip[c] = tf;  // v ≥ tf ⇔ v ≥ t for every float v
      u_min[c] = static_cast<float>(k.u_min[c]);
      area[c] = static_cast<float>(k.area[c]);
      gain[c] = static_cast<float>(k.inv_k2[c] * k.inv_eps);
      offset[c] = static_cast<float>(k.k1[c] * k.inv_eps);
      linear[c] = k.root[c]->linear();
      root[c] = k.root[c];
    }
  }
};

void check_frame(const FusedLuminance& out, const Normalisation& n, const RawImage& frame, size_t index) {
  const std::string what = "exposure " + std::to_string(index + 1);
  if (index >= static_cast<size_t>(kMaxExposures))
    throw Error(ErrorCode::LimitExceeded, "at most " + std::to_string(kMaxExposures) + " exposures can be combined");
  if (frame.width != out.width || frame.height != out.height)
    throw Error(ErrorCode::FrameMismatch, what + " is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                              " but the series is " + std::to_string(out.width) + "x" +
                                              std::to_string(out.height) + " (measurement pixels)");
  if (index > 0 && (frame.meta.make != out.make || frame.meta.model != out.model))
    throw Error(ErrorCode::FrameMismatch, what + " comes from " + frame.meta.make + " " + frame.meta.model +
                                              " but the series from " + out.make + " " + out.model);
  if (n.falloff && (n.falloff->width != frame.width || n.falloff->height != frame.height))
    throw Error(ErrorCode::FrameMismatch, what + ": the fall-off fit was made on an image of another size");
  if (frame.rgb.size() != static_cast<size_t>(frame.width) * frame.height * 3)
    throw Error(ErrorCode::InvalidArgument, what + " has no pixel data");
}

void count_sources(FusedLuminance& out) {
  out.dominant_pixels.assign(out.exposures.size(), 0);
  bool any = false;
  for (size_t p = 0; p < out.source.size(); ++p) {
    if (out.source[p] != 255) out.dominant_pixels[out.source[p]]++;
    if (out.contributors[p]) any = true;
    else out.unreliable_pixels++;
  }
  if (!any)
    throw Error(ErrorCode::NoUsableData, "no pixel has a reliable value in any exposure: every frame is "
                                         "saturated or below the noise floor");
}


#ifdef TRISTIM_SIMD4
// One row of ExposureFusion::add, four pixels per step (SSE2 natively, SIMD128 in wasm): the
// scalar loop's operations in its order, lane by lane (the same floats: std::min/max as min_std /
// max_std, a saturated channel's sums kept by a select instead of skipped), the table lookup of
// eq (8) lane by lane. Returns the pixels done (a multiple of 4); the scalar loop does the rest.
int add_row_simd(const FastKernel& k, const float* dx2, float dy2, float p1, float p2, float p3, const float* rgb,
                 const std::uint8_t* flags, int W, float* swl, float* sw, float* best, std::uint16_t* contributors,
                 std::uint8_t* source, std::uint16_t bit, std::uint8_t index8) {
  using namespace simd4;
  const f4 zero = splat(0.0f), one = splat(1.0f), tiny = splat(1e-6f), w = splat(k.w), eps = splat(k.eps);
  f4 clip[3], floor[3], inv_range[3], u_min[3], area[3], gain[3], offset[3], flag_bit[3];
  for (int c = 0; c < 3; ++c) {
    clip[c] = splat(k.clip[c]);
    floor[c] = splat(k.floor[c]);
    inv_range[c] = splat(k.inv_range[c]);
    u_min[c] = splat(k.u_min[c]);
    area[c] = splat(k.area[c]);
    gain[c] = splat(k.gain[c]);
    offset[c] = splat(k.offset[c]);
    flag_bit[c] = bits(1u << c);
  }
  const f4 P1 = splat(p1), P2 = splat(p2), P3 = splat(p3), DY2 = splat(dy2);
  const int n = W & ~3;
  for (int x = 0; x < n; x += 4) {
    f4 f = one;
    if (dx2) {
      const f4 r2 = add(load(dx2 + x), DY2);
      f = add(mul(P1, r2), P3);
      if (p2 != 0.0f) f = add(f, mul(P2, sqrt(r2)));
    }
    const f4 flag = flags ? load_bytes(flags + x) : bits(0);
    f4 V[3], SWL[3], SW[3];
    load_rgb(rgb + 3 * x, V[0], V[1], V[2]);
    load_rgb(swl + 3 * x, SWL[0], SWL[1], SWL[2]);
    load_rgb(sw + 3 * x, SW[0], SW[1], SW[2]);
    f4 reliability = zero;
    for (int c = 0; c < 3; ++c) {
      const f4 skip = bit_or(ge(V[c], clip[c]), int_eq(bit_and(flag, flag_bit[c]), flag_bit[c]));
      const f4 u = mul(sub(V[c], floor[c]), inv_range[c]);
      const f4 h = and_not(max_std(zero, min_std(one, min_std(mul(w, u), mul(w, sub(one, u))))), le(u, u_min[c]));
      const f4 weight = mul(max_std(h, tiny), eps);
      f4 R = mul(mul(u, area[c]), f);
      if (!k.linear[c]) {
        float r[4];
        store(r, R);
        for (float& v : r) v = k.root[c]->at(v);
        R = load(r);
      }
      const f4 L = sub(mul(R, gain[c]), offset[c]);
      SWL[c] = select(skip, SWL[c], add(SWL[c], mul(weight, L)));
      SW[c] = select(skip, SW[c], add(SW[c], weight));
      reliability = select(skip, reliability, add(reliability, mul(h, eps)));
    }
    store_xyz(swl + 3 * x, SWL[0], SWL[1], SWL[2]);
    store_xyz(sw + 3 * x, SW[0], SW[1], SW[2]);
    float rel[4];
    store(rel, reliability);
    for (int j = 0; j < 4; ++j) {
      if (rel[j] > 0) {
        contributors[x + j] |= bit;
        if (rel[j] > best[x + j]) {
          best[x + j] = rel[j];
          source[x + j] = index8;
        }
      }
    }
  }
  return n;
}
#endif
}  // namespace

ExposureFusion::ExposureFusion(const Normalisation& normalisation, const LuminanceFit& fit, int width, int height)
    : n_(normalisation), fit_(fit) {
  n_.check();
  if (width <= 0 || height <= 0) throw Error(ErrorCode::InvalidArgument, "fusion needs a positive image size");
  out_.width = width;
  out_.height = height;
}

void ExposureFusion::add(const RawImage& frame, const ExposureSettings& exposure) {
  const size_t index = out_.exposures.size();
  check_frame(out_, n_, frame, index);
  if (!(exposure.factor(fit_.iso_reference) > 0))
    throw Error(ErrorCode::MissingMetadata, "exposure " + std::to_string(index + 1) + " has no exposure time or f-number");
  const size_t npix = static_cast<size_t>(out_.width) * out_.height;
  if (index == 0) {
    out_.make = frame.meta.make;
    out_.model = frame.meta.model;
    detail::assign_large(sum_wL_, npix * 3, 0.0f);
    detail::assign_large(sum_w_, npix * 3, 0.0f);
    detail::assign_large(best_, npix, 0.0f);
    detail::assign_large(out_.source, npix, std::uint8_t{255});
    detail::assign_large(out_.contributors, npix, std::uint16_t{0});
  }
  out_.exposures.push_back(exposure);
  if (!tables_) tables_ = std::make_shared<const detail::FusionTables>(n_, fit_);
  const FrameKernel kd(n_, fit_, exposure, *tables_);
  const FastKernel k(kd, n_, exposure.factor(fit_.iso_reference));
  const std::uint16_t bit = static_cast<std::uint16_t>(1u << index);
  const bool has_flags = !frame.saturated.empty();
  const int W = out_.width;
  // f(r) = p1 r² + p2 r + p3 (eq 7) from r² = dx² + dy², in units of r_scale; the square root
  // only when p2 ≠ 0. dx² once per frame, dy² once per row.
  const FalloffFit* fo = n_.falloff ? &*n_.falloff : nullptr;
  std::vector<float> dx2(W, 0.0f);
  if (fo)
    for (int x = 0; x < W; ++x) {
      const double d = (x + 0.5 - fo->centre_x) / fo->r_scale;
      dx2[x] = static_cast<float>(d * d);
    }
  const float p1 = fo ? static_cast<float>(fo->p1) : 0.0f, p2 = fo ? static_cast<float>(fo->p2) : 0.0f,
              p3 = fo ? static_cast<float>(fo->p3) : 1.0f;
  const float* rgb = frame.rgb.data();
  const std::uint8_t* flags = has_flags ? frame.saturated.data() : nullptr;
  float* swl = sum_wL_.data();
  float* sw = sum_w_.data();
  float* best = best_.data();
  std::uint16_t* contributors = out_.contributors.data();
  std::uint8_t* source = out_.source.data();
  const std::uint8_t index8 = static_cast<std::uint8_t>(index);
  for (int y = 0; y < out_.height; ++y) {
    float dy2 = 0;
    if (fo) {
      const double d = (y + 0.5 - fo->centre_y) / fo->r_scale;
      dy2 = static_cast<float>(d * d);
    }
    const size_t row = static_cast<size_t>(y) * W;
#ifdef TRISTIM_SIMD4
    const int done = add_row_simd(k, fo ? dx2.data() : nullptr, dy2, p1, p2, p3, rgb + row * 3, flags ? flags + row : nullptr, W,
                                  swl + row * 3, sw + row * 3, best + row, contributors + row, source + row, bit, index8);
#else
    const int done = 0;
#endif
    for (int x = done; x < W; ++x) {
      const size_t p = row + x;
      float f = 1.0f;
      if (fo) {
        const float r2 = dx2[x] + dy2;
        f = p1 * r2 + p3;
        if (p2 != 0.0f) f += p2 * std::sqrt(r2);
      }
      const std::uint8_t flag = flags ? flags[p] : 0;
      float reliability = 0;
      for (int c = 0; c < 3; ++c) {
        const float v = rgb[p * 3 + c];
        if (v >= k.clip[c] || (flag >> c & 1)) continue;  // saturated: no contribution
        const float u = (v - k.floor[c]) * k.inv_range[c];
        const float h = u <= k.u_min[c] ? 0.0f : std::max(0.0f, std::min(1.0f, std::min(k.w * u, k.w * (1.0f - u))));
        const float weight = std::max(h, 1e-6f) * k.eps;
        const float R = u * k.area[c] * f;                                          // eq (7)
        const float L = (k.linear[c] ? R : k.root[c]->at(R)) * k.gain[c] - k.offset[c];  // eqs (8), (10)
        swl[p * 3 + c] += weight * L;
        sw[p * 3 + c] += weight;
        reliability += h * k.eps;
      }
      if (reliability > 0) {
        contributors[p] |= bit;
        if (reliability > best[p]) {
          best[p] = reliability;
          source[p] = index8;
        }
      }
    }
  }
}

#ifdef TRISTIM_SIMD4
// ExposureFusion::finish's loop four pixels (twelve sums) per step: the same IEEE division, NaN
// where no exposure contributed, and the pixels with such a channel counted from the comparison's
// lane bits (lane 3j + c is pixel j's channel c). Returns the pixels done (a multiple of 4).
static size_t finish_simd(float* swl, const float* sw, size_t npix, size_t& saturated) {
  using namespace simd4;
  const f4 zero = splat(0.0f), nan = splat(std::numeric_limits<float>::quiet_NaN());
  size_t p = 0;
  for (; p + 4 <= npix; p += 4) {
    int none = 0;  // bit l: lane l had no contribution
    for (int j = 0; j < 3; ++j) {
      const size_t at = 3 * p + 4 * static_cast<size_t>(j);
      const f4 w = load(sw + at), some = gt(w, zero);
      store(swl + at, select(some, div(load(swl + at), w), nan));
      none |= (~mask_bits(some) & 0xf) << (4 * j);
    }
    const int pixel = none | none >> 1 | none >> 2;  // bit 3j: any channel of pixel j
    saturated += static_cast<size_t>(__builtin_popcount(pixel & 0x249));
  }
  return p;
}
#endif

FusedLuminance ExposureFusion::finish() {
  if (out_.exposures.empty()) throw Error(ErrorCode::InvalidArgument, "no exposures were added");
  const size_t npix = static_cast<size_t>(out_.width) * out_.height;
  const float nan = std::numeric_limits<float>::quiet_NaN();
#ifdef TRISTIM_SIMD4
  size_t saturated_simd = 0;
  const size_t done = finish_simd(sum_wL_.data(), sum_w_.data(), npix, saturated_simd);
  out_.saturated_pixels += saturated_simd;
#else
  const size_t done = 0;
#endif
  for (size_t p = done; p < npix; ++p) {
    bool saturated = false;
    for (int c = 0; c < 3; ++c) {
      const float sw = sum_w_[p * 3 + c];
      if (sw > 0) sum_wL_[p * 3 + c] /= sw;
      else {
        sum_wL_[p * 3 + c] = nan;
        saturated = true;
      }
    }
    out_.saturated_pixels += saturated;
  }
  std::vector<float>().swap(sum_w_);
  std::vector<float>().swap(best_);
  out_.L = std::move(sum_wL_);
  count_sources(out_);
  FusedLuminance r = std::move(out_);
  out_ = FusedLuminance();
  return r;
}

FusedLuminance select_exposures_Guarnera2018(const std::vector<const RawImage*>& frames,
                                             const std::vector<ExposureSettings>& exposures,
                                             const Normalisation& n, const LuminanceFit& fit, int guess) {
  n.check();
  if (frames.empty()) throw Error(ErrorCode::InvalidArgument, "no exposures were given");
  if (exposures.size() != frames.size())
    throw Error(ErrorCode::InvalidArgument, "one exposure setting per frame is needed");
  FusedLuminance out;
  out.width = frames[0]->width;
  out.height = frames[0]->height;
  out.make = frames[0]->meta.make;
  out.model = frames[0]->meta.model;
  out.exposures = exposures;
  const detail::FusionTables tables(n, fit);
  std::vector<FrameKernel> kernels;
  for (size_t e = 0; e < frames.size(); ++e) {
    check_frame(out, n, *frames[e], e);
    if (!(exposures[e].factor(fit.iso_reference) > 0))
      throw Error(ErrorCode::MissingMetadata, "exposure " + std::to_string(e + 1) + " has no exposure time or f-number");
    kernels.emplace_back(n, fit, exposures[e], tables);
  }
  // The bracket in order of ε; the walk moves along it.
  std::vector<int> order(frames.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return exposures[a].factor(fit.iso_reference) < exposures[b].factor(fit.iso_reference);
  });
  int start = static_cast<int>(order.size() - 1) / 2;  // median ε
  if (guess >= 0) {
    if (guess >= static_cast<int>(frames.size()))
      throw Error(ErrorCode::InvalidArgument, "the initial exposure index is outside the series");
    start = static_cast<int>(std::find(order.begin(), order.end(), guess) - order.begin());
  }
  const size_t npix = static_cast<size_t>(out.width) * out.height;
  out.L.assign(npix * 3, 0.0f);
  out.source.assign(npix, 255);
  out.contributors.assign(npix, 0);
  const int last = static_cast<int>(order.size()) - 1;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const size_t p = static_cast<size_t>(y) * out.width + x;
      const double f = n.falloff_factor(x, y);
      bool saturated = false;
      for (int c = 0; c < 3; ++c) {
        auto zone_at = [&](int k) {
          const RawImage& fr = *frames[order[k]];
          const bool flagged = !fr.saturated.empty() && (fr.saturated[p] >> c & 1);
          return n.zone(c, fr.rgb[p * 3 + c], flagged);
        };
        // ESTLUMINANCE: Z_c -> use; Z_u -> longer; Z_o / saturated -> shorter (Algorithm 1).
        int k = start, chosen = -1, dir = 0;
        while (chosen < 0) {
          const Zone z = zone_at(k);
          if (z == Zone::Centre) chosen = k;
          else if (z == Zone::Under) {
            if (dir >= 0 && k < last) { dir = 1; ++k; }
            else chosen = (dir < 0 && zone_at(k + 1) == Zone::Over) ? k + 1 : k;  // reversal: prefer Z_o
          } else {
            if (dir <= 0 && k > 0) { dir = -1; --k; }
            else if (dir > 0) chosen = z == Zone::Over ? k : k - 1;  // reversal after Z_u
            else chosen = z == Zone::Over ? k : -2;                   // shortest exposure saturated
          }
          if (chosen == -2) break;
        }
        if (chosen < 0) {
          out.L[p * 3 + c] = std::numeric_limits<float>::quiet_NaN();
          saturated = true;
          continue;
        }
        const int e = order[chosen];
        const FrameKernel& kern = kernels[e];
        const double v = frames[e]->rgb[p * 3 + c];
        out.L[p * 3 + c] = static_cast<float>(kern.luminance(c, (v - kern.floor[c]) * kern.inv_range[c], f));
        if (reliability_Guarnera2018(zone_at(chosen), (v - kern.floor[c]) * kern.inv_range[c], n.w, kern.u_min[c]) > 0)
          out.contributors[p] |= static_cast<std::uint16_t>(1u << e);
        if (c == 1) out.source[p] = static_cast<std::uint8_t>(e);
      }
      out.saturated_pixels += saturated;
    }
  count_sources(out);
  return out;
}

}  // namespace tristim

// Frame calibration: dark frames, flat field (Abed 2013 App. C), radial fall-off (Guarnera 2018).
#include "tristim/capture/calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "../citations.hpp"
#include "../large_buffer.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

// Size and camera of a frame: enough to tell whether two frames can be combined.
struct FrameId {
  int width, height;
  const std::string& make;
  const std::string& model;
};
FrameId frame_id(const RawImage& r) { return {r.width, r.height, r.meta.make, r.meta.model}; }
FrameId frame_id(const DarkFrame& d) { return {d.width, d.height, d.make, d.model}; }
FrameId frame_id(const FlatField& f) { return {f.width, f.height, f.make, f.model}; }

// FrameMismatch unless `other` (named `what`) has the image's size and camera.
void require_same(const FrameId& image, const FrameId& other, const std::string& what) {
  if (other.width != image.width || other.height != image.height)
    throw Error(ErrorCode::FrameMismatch,
                what + " is " + std::to_string(other.width) + " x " + std::to_string(other.height) +
                    " but the image is " + std::to_string(image.width) + " x " +
                    std::to_string(image.height) + " (measurement pixels)");
  if (other.make != image.make || other.model != image.model)
    throw Error(ErrorCode::FrameMismatch, what + " comes from " + other.make + " " + other.model +
                                              " but the image from " + image.make + " " + image.model);
}

}  // namespace

DarkFrame average_dark_frames(const std::vector<const RawImage*>& frames) {
  if (frames.empty() || !frames[0])
    throw Error(ErrorCode::InvalidArgument, "no dark frames given");
  const RawImage& first = *frames[0];
  DarkFrame d;
  d.width = first.width;
  d.height = first.height;
  d.make = first.meta.make;
  d.model = first.meta.model;
  d.frames = static_cast<int>(frames.size());
  const size_t n = first.rgb.size();
  for (size_t k = 0; k < frames.size(); ++k) {
    if (!frames[k]) throw Error(ErrorCode::InvalidArgument, "dark frame " + std::to_string(k + 1) + " is missing");
    require_same(frame_id(d), frame_id(*frames[k]), "dark frame " + std::to_string(k + 1));
  }
  // Sum each element over the frames in double (no second full-size buffer: memory matters in wasm).
  detail::reserve_large(d.rgb, n);
  d.rgb.resize(n);
  std::array<double, 3> sum{};
  const double inv = 1.0 / frames.size();
  if (frames.size() == 1) {
    const float* a = first.rgb.data();
    for (size_t i = 0; i < n; ++i) d.rgb[i] = static_cast<float>(static_cast<double>(a[i]) * inv);
  } else {
    for (size_t i = 0; i < n; ++i) {
      double acc = 0;
      for (const RawImage* f : frames) acc += f->rgb[i];
      d.rgb[i] = static_cast<float>(acc * inv);
    }
  }
  for (size_t i = 0; i + 2 < n; i += 3)
    for (int c = 0; c < 3; ++c) sum[c] += d.rgb[i + c];
  const double npix = static_cast<double>(n / 3);
  for (int c = 0; c < 3; ++c) d.mean[c] = sum[c] / npix;
  // Noise floor: spread of one frame around the average (temporal + fixed-pattern residual).
  // Pixel by pixel, the three channels' sums apart (the same additions in the same order as
  // element by element with i % 3, without a division per element and a sum kept in memory).
  std::array<double, 3> ss{};
  const bool several = frames.size() > 1;
  for (size_t i = 0; i + 2 < n; i += 3)
    for (int c = 0; c < 3; ++c) {
      const double e = first.rgb[i + c] - (several ? d.rgb[i + c] : d.mean[c]);
      ss[c] += e * e;
    }
  const double dof = frames.size() > 1 ? npix * (1.0 - 1.0 / frames.size()) : npix - 1;
  for (int c = 0; c < 3; ++c) d.noise[c] = std::sqrt(ss[c] / std::max(1.0, dof));
  return d;
}

const std::vector<MethodInfo>& flat_field_methods() {
  static const std::vector<MethodInfo> table = {
      {"pixel", "Per pixel (a gain at every pixel)",
       std::string(citation::kAbed2013) + ", App. C step 2", {}},
      {"radial", "Radial fall-off fit (a smooth lens fall-off)",
       std::string(citation::kGuarnera2018) + ", eq (7)", {}},
  };
  return table;
}

const char* dark_mode_id(DarkMode mode) { return mode == DarkMode::PerChannel ? "per_channel" : "per_pixel"; }

DarkMode dark_mode_from_id(std::string_view id) {
  if (id == "per_pixel" || id == "pixel") return DarkMode::PerPixel;
  if (id == "per_channel" || id == "channel") return DarkMode::PerChannel;
  throw Error(ErrorCode::InvalidArgument,
              "dark mode '" + std::string(id) + "' is not per_pixel or per_channel (aliases: pixel, channel)");
}

FlatField make_flat_field(const RawImage& flat, const DarkFrame* dark, DarkMode dark_mode,
                          const std::optional<std::array<double, 3>>& white_reflectance) {
  FlatField f;
  f.width = flat.width;
  f.height = flat.height;
  f.make = flat.meta.make;
  f.model = flat.meta.model;
  if (dark) require_same(frame_id(flat), frame_id(*dark), "the dark frame");
  if (white_reflectance)
    for (double r : *white_reflectance)
      if (!(r > 0 && r <= 1.5))
        throw Error(ErrorCode::InvalidArgument, "white reflectance must be in (0, 1.5], got " + std::to_string(r));
  const size_t n = flat.rgb.size();
  // Two passes over the flat (check + channel sums, then gains) instead of a second full-size buffer.
  // Element i + c of pixel i / 3 (channel c): the flat minus the dark (per pixel, or its channel mean).
  const bool per_pixel = dark && dark_mode == DarkMode::PerPixel;
  float dark_mean[3] = {0.f, 0.f, 0.f};
  if (dark)
    for (int c = 0; c < 3; ++c) dark_mean[c] = static_cast<float>(dark->mean[c]);
  const auto signal = [&](size_t i, int c) { return flat.rgb[i + c] - (per_pixel ? dark->rgb[i + c] : dark_mean[c]); };
  std::array<double, 3> sum{};
  bool positive = true;
  for (size_t i = 0; i + 2 < n; i += 3)
    for (int c = 0; c < 3; ++c) {
      const float v = signal(i, c);
      positive &= v > 0;
      sum[c] += v;
    }
  if (!positive)  // the first element that is not, named
    for (size_t i = 0; i + 2 < n; i += 3)
      for (int c = 0; c < 3; ++c)
        if (!(signal(i, c) > 0)) {
          const size_t p = i / 3;
          throw Error(ErrorCode::FlatFieldZero,
                      "the flat field has a zero or negative value at pixel (" + std::to_string(p % flat.width) +
                          ", " + std::to_string(p / flat.width) + ") channel " + "RGB"[c] +
                          ": expose the flat so every pixel has signal");
        }
  const double npix = static_cast<double>(n / 3);
  f.reflectance_units = white_reflectance.has_value();
  for (int c = 0; c < 3; ++c) f.target[c] = white_reflectance ? (*white_reflectance)[c] : sum[c] / npix;
  detail::reserve_large(f.gain, n);
  f.gain.resize(n);
  for (size_t i = 0; i + 2 < n; i += 3)
    for (int c = 0; c < 3; ++c) f.gain[i + c] = static_cast<float>(f.target[c] / signal(i, c));  // App. C step 2
  return f;
}

double FalloffFit::factor(double x, double y) const {
  const double dx = x - centre_x, dy = y - centre_y;  // sqrt, not hypot: per pixel, and slow in wasm
  const double r = std::sqrt(dx * dx + dy * dy) / r_scale;
  return p1 * r * r + p2 * r + p3;  // eq (7): f(u_p, v_p)
}

namespace fields {
TRISTIM_FIELDS_DEFINE(FalloffFit, member<&FalloffFit::p1>("p1"), member<&FalloffFit::p2>("p2"),
                      member<&FalloffFit::p3>("p3"), member<&FalloffFit::centre_x>("centre_x"),
                      member<&FalloffFit::centre_y>("centre_y"), member<&FalloffFit::r_scale>("r_scale"),
                      member<&FalloffFit::width>("width"), member<&FalloffFit::height>("height"),
                      member<&FalloffFit::bins>("bins"), member<&FalloffFit::rms_residual>("rms_residual"),
                      member<&FalloffFit::max_residual>("max_residual"));
}  // namespace fields

FalloffFit fit_falloff_Guarnera2018(const RawImage& flat, const DarkFrame* dark) {
  if (dark) require_same(frame_id(flat), frame_id(*dark), "the dark frame");
  FalloffFit fit;
  fit.width = flat.width;
  fit.height = flat.height;
  fit.centre_x = flat.width / 2.0;
  fit.centre_y = flat.height / 2.0;
  fit.r_scale = std::sqrt(fit.centre_x * fit.centre_x + fit.centre_y * fit.centre_y);  // not hypot: the same bits in every build
  const size_t npix = static_cast<size_t>(flat.width) * flat.height;
  // Per-channel means (for normalising the channels to a common scale).
  std::array<double, 3> mean{};
  size_t used = 0;
  for (size_t p = 0; p < npix; ++p) {
    if (flat.saturated[p]) continue;
    for (int c = 0; c < 3; ++c) mean[c] += flat.rgb[p * 3 + c] - (dark ? dark->rgb[p * 3 + c] : 0.0f);
    ++used;
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = used ? mean[c] / used : 0;
    if (!(mean[c] > 0))
      throw Error(ErrorCode::FlatFieldZero, "the flat field has no positive signal in channel " +
                                                std::string(1, "RGB"[c]));
  }
  const double inv_mean[3] = {1.0 / (3 * mean[0]), 1.0 / (3 * mean[1]), 1.0 / (3 * mean[2])};
  constexpr int kBins = 64;
  std::vector<double> bsum(kBins, 0), bcount(kBins, 0), brsum(kBins, 0);
  for (int y = 0; y < flat.height; ++y)
    for (int x = 0; x < flat.width; ++x) {
      const size_t p = static_cast<size_t>(y) * flat.width + x;
      if (flat.saturated[p]) continue;
      double L = 0;
      for (int c = 0; c < 3; ++c) L += (flat.rgb[p * 3 + c] - (dark ? dark->rgb[p * 3 + c] : 0.0f)) * inv_mean[c];
      const double dx = x + 0.5 - fit.centre_x, dy = y + 0.5 - fit.centre_y;
      const double r = std::sqrt(dx * dx + dy * dy) / fit.r_scale;
      const int b = std::min(kBins - 1, static_cast<int>(r * kBins));
      bsum[b] += L;
      brsum[b] += r;
      bcount[b] += 1;
    }
  std::vector<double> rs, Ls, ws;
  for (int b = 0; b < kBins; ++b)
    if (bcount[b] > 0) {
      rs.push_back(brsum[b] / bcount[b]);
      Ls.push_back(bsum[b] / bcount[b]);
      ws.push_back(std::sqrt(bcount[b]));
    }
  const int m = static_cast<int>(rs.size());
  if (m < 3) throw Error(ErrorCode::InvalidArgument, "the flat field is too small to fit a radial fall-off");
  for (double L : Ls)
    if (!(L > 0)) throw Error(ErrorCode::FlatFieldZero, "the flat field has a ring without positive signal");
  // f(r) = L(0) / L(r) = p1 r² + p2 r + 1  <=>  1 / L(r) = a + b r + c r² with L(0) = 1/a,
  // p2 = b/a, p1 = c/a: one linear least-squares fit (rows weighted by L·sqrt(count), i.e.
  // relative errors), and f(centre) = 1 by construction.
  Eigen::MatrixXd A(m, 3);
  Eigen::VectorXd t(m);
  for (int i = 0; i < m; ++i) {
    const double w = ws[i] * Ls[i];
    A(i, 0) = w;
    A(i, 1) = w * rs[i];
    A(i, 2) = w * rs[i] * rs[i];
    t(i) = w / Ls[i];
  }
  const Eigen::Vector3d q = A.colPivHouseholderQr().solve(t);
  if (!(q(0) > 0)) throw Error(ErrorCode::FlatFieldZero, "the flat field's centre has no positive signal");
  const double L0 = 1.0 / q(0);
  fit.p1 = q(2) / q(0);
  fit.p2 = q(1) / q(0);
  fit.p3 = 1.0;
  fit.bins = m;
  double ss = 0, wsum = 0;
  for (int i = 0; i < m; ++i) {
    const double f = fit.p1 * rs[i] * rs[i] + fit.p2 * rs[i] + fit.p3;
    const double e = f * Ls[i] / L0 - 1.0;
    ss += ws[i] * ws[i] * e * e;
    wsum += ws[i] * ws[i];
    fit.max_residual = std::max(fit.max_residual, std::abs(e));
  }
  fit.rms_residual = std::sqrt(ss / wsum);
  return fit;
}

void FrameCalibration::check_compatible(const RawImage& image) const {
  if (dark) require_same(frame_id(image), frame_id(*dark), "the dark frame");
  if (flat) require_same(frame_id(image), frame_id(*flat), "the flat field");
  if (falloff && (falloff->width != image.width || falloff->height != image.height))
    throw Error(ErrorCode::FrameMismatch, "the fall-off fit was made on an image of another size");
}

void FrameCalibration::dark_subtracted(const RawImage& image, int x, int y, float out[3]) const {
  const size_t i = (static_cast<size_t>(y) * image.width + x) * 3;
  for (int c = 0; c < 3; ++c) {
    float v = image.rgb[i + c];
    if (dark) v -= dark_mode == DarkMode::PerPixel ? dark->rgb[i + c] : static_cast<float>(dark->mean[c]);
    out[c] = v;
  }
}

void FrameCalibration::calibrated(const RawImage& image, int x, int y, float out[3]) const {
  dark_subtracted(image, x, y, out);
  if (flare)
    for (int c = 0; c < 3; ++c) out[c] -= static_cast<float>((*flare)[c]);
  const size_t i = (static_cast<size_t>(y) * image.width + x) * 3;
  if (flat)
    for (int c = 0; c < 3; ++c) out[c] *= flat->gain[i + c];
  if (falloff) {
    const float f = static_cast<float>(falloff->factor(x + 0.5, y + 0.5));
    for (int c = 0; c < 3; ++c) out[c] *= f;
  }
}

std::array<double, 3> FrameCalibration::noise_floor() const {
  return dark ? dark->noise : std::array<double, 3>{0, 0, 0};
}

FrameCalibration with_dark_frames(FrameCalibration base, const RawImage& image,
                                  const std::vector<const RawImage*>& frames, std::string_view mode) {
  for (const RawImage* f : frames)
    if (!f) throw Error(ErrorCode::InvalidArgument, "a dark frame is missing (null)");
  base.dark = average_dark_frames(frames);
  base.dark_mode = mode.empty() ? DarkMode::PerPixel : dark_mode_from_id(mode);
  base.check_compatible(image);
  return base;
}

FrameCalibration with_flat_frame(FrameCalibration base, const RawImage& image, const RawImage& flat, std::string_view mode,
                                 const std::vector<double>& white_reflectance) {
  const DarkFrame* dark = base.dark ? &*base.dark : nullptr;
  if (mode == "radial") {
    base.falloff = fit_falloff_Guarnera2018(flat, dark);
    base.flat.reset();
  } else if (mode.empty() || mode == "pixel") {
    std::optional<std::array<double, 3>> white;
    const std::vector<double>& w = white_reflectance;
    if (w.size() == 1) white = std::array<double, 3>{w[0], w[0], w[0]};
    else if (w.size() == 3) white = std::array<double, 3>{w[0], w[1], w[2]};
    else if (!w.empty())
      throw Error(ErrorCode::InvalidArgument, "the white reflectance is one value or three (R, G, B), got " +
                                                  std::to_string(w.size()));
    base.flat = make_flat_field(flat, dark, base.dark_mode, white);
    base.falloff.reset();
  } else {
    throw Error(ErrorCode::InvalidArgument, "flat mode is 'pixel' or 'radial', not '" + std::string(mode) + "'");
  }
  base.check_compatible(image);
  return base;
}

RawImage apply_calibration(const RawImage& image, const FrameCalibration& calibration) {
  calibration.check_compatible(image);
  RawImage out;
  out.meta = image.meta;
  out.width = image.width;
  out.height = image.height;
  detail::copy_large(out.saturated, image.saturated);
  detail::reserve_large(out.rgb, image.rgb.size());
  // Row by row into a row buffer that stays in L1/L2, appended to the output (no resize of the
  // whole output first: its zero fill would be one more write pass, 72 MB at 24 MP). One fused
  // pass reads the image, dark and gain rows together; a missing part is a neutral row (x - 0 and
  // x · 1 are exact), so every element gets the same float operations in the same order as
  // FrameCalibration::calibrated: ((v - dark) - flare) · gain · fall-off (identical results).
  const size_t w = static_cast<size_t>(image.width), n3 = 3 * w;
  const auto& dark = calibration.dark;
  const bool dark_per_pixel = dark && calibration.dark_mode == DarkMode::PerPixel;
  std::vector<float> dark_row(n3, 0.f), flare_row(n3, 0.f), ones(n3, 1.f), row(n3), fall(w);
  if (dark && !dark_per_pixel)  // the per-channel means, repeated along a row
    for (size_t i = 0; i < n3; ++i) dark_row[i] = static_cast<float>(dark->mean[i % 3]);
  if (calibration.flare)
    for (size_t i = 0; i < n3; ++i) flare_row[i] = static_cast<float>((*calibration.flare)[i % 3]);
  const FalloffFit* falloff = calibration.falloff ? &*calibration.falloff : nullptr;
  for (size_t y = 0; y < static_cast<size_t>(image.height); ++y) {
    const float* __restrict in = &image.rgb[y * n3];
    const float* __restrict sub = dark_per_pixel ? &dark->rgb[y * n3] : dark_row.data();
    const float* __restrict fl = flare_row.data();
    const float* __restrict g = calibration.flat ? &calibration.flat->gain[y * n3] : ones.data();
    float* __restrict o = row.data();
    for (size_t i = 0; i < n3; ++i) o[i] = ((in[i] - sub[i]) - fl[i]) * g[i];
    if (falloff) {
      // FalloffFit::factor at pixel centres (x + 0.5, y + 0.5), eq (7).
      const double dy = (static_cast<double>(y) + 0.5) - falloff->centre_y, dy2 = dy * dy;
      const double p1 = falloff->p1, p2 = falloff->p2, p3 = falloff->p3, rs = falloff->r_scale;
      const double cx = falloff->centre_x;
      for (size_t x = 0; x < w; ++x) {
        const double dx = (static_cast<double>(x) + 0.5) - cx;
        const double r = std::sqrt(dx * dx + dy2) / rs;
        fall[x] = static_cast<float>(p1 * r * r + p2 * r + p3);
      }
      for (size_t x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) o[3 * x + c] *= fall[x];
    }
    out.rgb.insert(out.rgb.end(), o, o + n3);
  }
  return out;
}

}  // namespace tristim

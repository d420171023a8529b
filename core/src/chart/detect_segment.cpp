// Chart detection, steps 1-3: working image, flat regions, patch quadrilaterals (detect.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"
#include "../detmath.hpp"
#include "../capture/percentile.hpp"
#include "../large_buffer.hpp"

namespace tristim {

namespace {

using Point = Eigen::Vector2d;

double cross2(const Point& o, const Point& a, const Point& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain; returns the hull in the order of increasing signed area (clockwise
// on screen with y down).
std::vector<Point> convex_hull(std::vector<Point> pts) {
  std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (pts.size() < 3) return pts;
  std::vector<Point> hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

double polygon_area(const std::vector<Point>& p) {  // signed; > 0 = clockwise on screen (y down)
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Point& q = p[i];
    const Point& r = p[(i + 1) % p.size()];
    a += q.x() * r.y() - r.x() * q.y();
  }
  return a / 2;
}

}  // namespace

namespace {

// The box mean of working_image for a factor F known at compile time (the loops over a block
// unroll and vectorise; F = 0: the factor f at run time). Per output value the float operations
// are the same either way: each input row's F values summed in order, those row sums added in
// order of the rows, the total times 1/(F·F).
template <int F>
void box_downsample(const RawImage& image, int f, RawImage& out) {
  if (F > 0) f = F;
  const bool has_sat = image.saturated.size() == size_t(image.width) * image.height;
  const float norm = 1.f / float(f * f);
  const int ow = out.width;
  for (int y = 0; y < out.height; ++y) {
    float* row = &out.rgb[size_t(y) * ow * 3];
    std::uint8_t* sat = out.saturated.empty() ? nullptr : &out.saturated[size_t(y) * ow];
    for (int yy = y * f; yy < (y + 1) * f; ++yy) {
      const float* src = &image.rgb[size_t(yy) * image.width * 3];
      for (int x = 0; x < ow; ++x) {
        const float* p = src + size_t(x) * f * 3;
        float s0 = 0, s1 = 0, s2 = 0;
        for (int k = 0; k < f; ++k) {
          s0 += p[k * 3];
          s1 += p[k * 3 + 1];
          s2 += p[k * 3 + 2];
        }
        row[x * 3] += s0;
        row[x * 3 + 1] += s1;
        row[x * 3 + 2] += s2;
      }
      if (has_sat) {
        const std::uint8_t* in = &image.saturated[size_t(yy) * image.width];
        for (int x = 0; x < ow; ++x) {
          std::uint8_t m = 0;
          for (int k = 0; k < f; ++k) m |= in[x * f + k];
          sat[x] |= m;
        }
      }
    }
    for (int i = 0; i < ow * 3; ++i) row[i] *= norm;
  }
}

}  // namespace

RawImage working_image(const RawImage& image, int working_side, int* factor_out) {
  if (image.width < 1 || image.height < 1 || image.rgb.size() != size_t(image.width) * image.height * 3)
    throw Error(ErrorCode::InvalidArgument, "chart detection needs a non-empty RGB image");
  const int side = std::max(image.width, image.height);
  const int f = std::max(1, (side + std::max(1, working_side) - 1) / std::max(1, working_side));
  if (factor_out) *factor_out = f;
  if (f == 1) return image;
  RawImage out;
  out.meta = image.meta;
  out.width = image.width / f;
  out.height = image.height / f;
  // Pages mapped in one call natively (large_buffer.hpp): a 24 MP image's working copy is
  // ~20 MB, ~5000 page faults otherwise.
  detail::assign_large(out.rgb, size_t(out.width) * out.height * 3, 0.f);
  detail::assign_large(out.saturated, size_t(out.width) * out.height, std::uint8_t(0));
  switch (f) {
    case 2: box_downsample<2>(image, f, out); break;
    case 3: box_downsample<3>(image, f, out); break;
    case 4: box_downsample<4>(image, f, out); break;
    default: box_downsample<0>(image, f, out); break;
  }
  return out;
}

namespace {

// Splits v[lo, hi) into `bins` parts of equal count (bin k: the k-th `bins`-quantile range of
// the key), each part's members before the next part's, by recursive nth_element: the same
// bins as a full sort, O(n log bins) instead of O(n log n). bounds[k] = first index of bin k.
template <class T, class Less>
void quantile_split(std::vector<T>& v, size_t lo, size_t hi, int k0, int k1, int bins, Less less) {
  if (k1 - k0 < 2) return;
  const int km = (k0 + k1) / 2;
  const size_t m = v.size() * static_cast<size_t>(km) / static_cast<size_t>(bins);
  std::nth_element(v.begin() + static_cast<std::ptrdiff_t>(lo), v.begin() + static_cast<std::ptrdiff_t>(m),
                   v.begin() + static_cast<std::ptrdiff_t>(hi), less);
  quantile_split(v, lo, m, k0, km, bins, less);
  quantile_split(v, m, hi, km, k1, bins, less);
}

}  // namespace

NoiseModel estimate_noise(const RawImage& img) {
  NoiseModel model;
  const int w = img.width, h = img.height;
  if (w < 8 || h < 8) return model;
  std::vector<std::pair<float, float>> sd;
  sd.reserve(size_t(w / 2) * size_t(h / 2));
  std::vector<float> level, dev;
  for (int c = 0; c < 3; ++c) {
    // d = I(x) - (I(x-1) + I(x+1)) / 2 has variance 1.5 σ² where the image is flat.
    sd.clear();
    for (int y = 1; y < h - 1; y += 2) {
      const float* row = &img.rgb[size_t(y) * w * 3 + size_t(c)];
      for (int x = 1; x < w - 1; x += 2) {
        const float i = row[x * 3];
        sd.emplace_back(i, i - 0.5f * (row[(x - 1) * 3] + row[(x + 1) * 3]));
      }
    }
    // 24 bins of equal count in order of level: the median level and the MAD-based variance of each.
    // The (level, deviation) pairs are compared whole: pairs of equal level (whole DN are common)
    // fall into the same bins with libstdc++'s nth_element and libc++'s (native and wasm).
    constexpr int kBins = 24;
    quantile_split(sd, 0, sd.size(), 0, kBins, kBins, [](const auto& a, const auto& b) { return a < b; });
    Eigen::MatrixXd A(kBins, 2);
    Eigen::VectorXd b(kBins), wt(kBins);
    for (int k = 0; k < kBins; ++k) {
      const size_t lo = sd.size() * k / kBins, hi = sd.size() * (k + 1) / kBins;
      level.clear();
      dev.clear();
      for (size_t i = lo; i < hi; ++i) {
        level.push_back(sd[i].first);
        dev.push_back(std::abs(sd[i].second));
      }
      const double I = std::max(0.f, percentile(level, 0.5)), mad = percentile(dev, 0.5);
      A(k, 0) = I;
      A(k, 1) = 1;
      b(k) = (1.4826 * mad) * (1.4826 * mad) / 1.5;
      wt(k) = 1;
    }
    // σ² = a·I + b, least squares with textured bins (far above the line) down-weighted.
    Eigen::Vector2d ab(0, b.minCoeff());
    for (int it = 0; it < 4; ++it) {
      const Eigen::MatrixXd Aw = wt.asDiagonal() * A;
      ab = (Aw.transpose() * A).ldlt().solve(Aw.transpose() * b);
      for (int k = 0; k < kBins; ++k) {
        const double fit = std::max(1e-30, ab[0] * A(k, 0) + ab[1]);
        wt(k) = b(k) > 2 * fit ? 0.05 : 1.0;
      }
    }
    model.gain[c] = std::max(0.0, ab[0]);
    model.floor[c] = std::max(ab[1], 1e-4 * b.maxCoeff() + 1e-30);
  }
  return model;
}

RegionLabels flat_regions(const RawImage& img, const FlatRegionOptions& options) {
  const int w = img.width, h = img.height;
  RegionLabels out;
  out.width = w;
  out.height = h;
  detail::assign_large(out.label, size_t(w) * h, -1);  // pages mapped in one call natively (large_buffer.hpp)
  if (w < 5 || h < 5) return out;
  const NoiseModel noise = estimate_noise(img);
  // The image is streamed row by row through rings of three rows (3×3 box mean, log, flat
  // test, erosion): no image-sized intermediate buffers, whose allocation (page faults) cost
  // more than the arithmetic. The 3×3 box mean: a horizontal pass (the mean of the pixels
  // inside the image), then a vertical one, in this order of float operations.
  // Each loop below runs over the row's floats in order (no per-channel branch), so the compiler
  // can vectorise it; the float operations per value are the same as a per-pixel loop's.
  const size_t rw = size_t(w) * 3;
  auto horizontal = [&](int y, float* dst) {
    const float* in = &img.rgb[size_t(y) * rw];
    for (size_t i = 0; i < 3; ++i) dst[i] = (in[i] + in[i + 3]) / 2.f;  // x = 0
    for (size_t i = 3; i < rw - 3; ++i) dst[i] = (in[i - 3] + in[i] + in[i + 3]) / 3.f;
    for (size_t i = rw - 3; i < rw; ++i) dst[i] = (in[i - 3] + in[i]) / 2.f;  // x = w - 1
  };
  // log(RGB + eps): ratio edges count the same in light and shade (vignetting, uneven light).
  // eps from the 99th percentile of the smoothed image on every 7th pixel.
  float eps[3];
  {
    std::vector<float> v[3];
    for (auto& vc : v) vc.reserve(size_t(w) * h / 7 + 1);
    for (size_t p = 0; p < size_t(w) * h; p += 7) {
      const int x = static_cast<int>(p % w), y = static_cast<int>(p / w);
      const int x0 = std::max(0, x - 1), x1 = std::min(w - 1, x + 1);
      const int y0 = std::max(0, y - 1), y1 = std::min(h - 1, y + 1);
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int yy = y0; yy <= y1; ++yy) {
          float t = 0;
          for (int xx = x0; xx <= x1; ++xx) t += img.rgb[size_t(yy) * rw + size_t(xx) * 3 + c];
          s += t / float(x1 - x0 + 1);
        }
        v[c].push_back(s / float(y1 - y0 + 1));
      }
    }
    for (int c = 0; c < 3; ++c) eps[c] = std::max(1e-6f, 0.002f * percentile(v[c], 0.99));
  }
  // Rings indexed by row % 3: horizontal means, logs, the 3×3 means (clipped at 0), flat flags.
  std::vector<float> hor(3 * rw), logs(3 * rw), means(3 * rw), eps_row(rw);
  std::vector<std::uint8_t> flat(size_t(3) * w, 0);
  for (size_t i = 0; i < rw; ++i) eps_row[i] = eps[i % 3];
  auto hrow = [&](int y) { return &hor[size_t(y % 3) * rw]; };
  auto lrow = [&](int y) { return &logs[size_t(y % 3) * rw]; };
  auto mrow = [&](int y) { return &means[size_t(y % 3) * rw]; };
  auto frow = [&](int y) { return &flat[size_t(y % 3) * w]; };
  // Row y of the log image (and the 3×3 mean the flat test takes its noise from): needs
  // horizontal rows y±1.
  auto log_row = [&](int y) {
    const int y0 = std::max(0, y - 1), y1 = std::min(h - 1, y + 1);
    const float n = float(y1 - y0 + 1);
    float* L = lrow(y);
    float* M = mrow(y);
    const float *a = hrow(y0), *b = hrow(y0 + 1), *c = hrow(y1);
    if (y1 - y0 == 2) {
      for (size_t i = 0; i < rw; ++i) M[i] = std::max(0.f, (a[i] + b[i] + c[i]) / n);
    } else {
      for (size_t i = 0; i < rw; ++i) M[i] = std::max(0.f, (a[i] + b[i]) / n);
    }
    for (size_t i = 0; i < rw; ++i) L[i] = M[i] + eps_row[i];
    detmath::log_float_n(L, L, rw);  // the same bits in every build
  };
  // Noise of half a central difference of log(3×3 mean) at value i of row y:
  // σ(I)/3 · √2 / 2 / (I + eps).
  auto sigma = [&](int y, size_t i) {
    const int c = static_cast<int>(i % 3);
    const float m = mrow(y)[i], v = m + eps[c];
    return static_cast<float>(std::sqrt(noise.gain[c] * m + noise.floor[c]) / 3 * 0.7071 / v);
  };
  // Flat: in every channel both half central differences stay below noise_multiple σ (and the
  // min_step floor; σ is only computed when the step exceeds the floor). Row y needs log rows
  // y±1 and row y's means.
  const float k = static_cast<float>(options.noise_multiple), floor = static_cast<float>(options.min_step);
  auto flat_row = [&](int y) {
    std::uint8_t* F = frow(y);
    std::fill(F, F + w, std::uint8_t(0));
    if (y < 1 || y > h - 2) return;
    const float *up = lrow(y - 1), *mid = lrow(y), *dn = lrow(y + 1);
    for (int x = 1; x < w - 1; ++x) {
      bool ok = true;
      for (int c = 0; c < 3 && ok; ++c) {
        const size_t i = size_t(x) * 3 + c;
        const float g = 0.5f * std::max(std::abs(mid[i + 3] - mid[i - 3]), std::abs(dn[i] - up[i]));
        ok = g < floor || g < k * sigma(y, i);
      }
      F[x] = ok;
    }
  };
  // Erode once (3×3): thin bridges between neighbouring patches break. The core pixels are
  // marked -2 in the label image (-1 elsewhere) for the connected components below.
  auto erode_row = [&](int y) {
    if (y < 1 || y > h - 2) return;
    const std::uint8_t *a = frow(y - 1), *b = frow(y), *c = frow(y + 1);
    int* L = &out.label[size_t(y) * w];
    for (int x = 1; x < w - 1; ++x)
      if (a[x - 1] & a[x] & a[x + 1] & b[x - 1] & b[x] & b[x + 1] & c[x - 1] & c[x] & c[x + 1]) L[x] = -2;
  };
  // Pipeline at step y: horizontal row y+1 -> log row y -> flat row y-1 -> eroded row y-2.
  horizontal(0, hrow(0));
  for (int y = 0; y < h; ++y) {
    if (y + 1 < h) horizontal(y + 1, hrow(y + 1));
    log_row(y);
    if (y >= 1) flat_row(y - 1);
    if (y >= 2) erode_row(y - 2);
  }
  flat_row(h - 1);
  erode_row(h - 2);
  // 4-connected components (explicit stack), numbered in raster order of their first pixel.
  std::vector<int> stack;
  std::vector<int>& label = out.label;
  for (size_t start = 0; start < label.size(); ++start) {
    if (label[start] != -2) continue;
    const int id = out.count++;
    label[start] = id;
    stack.assign(1, static_cast<int>(start));
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int x = i % w, y = i / w;
      const int nb[4] = {x > 0 ? i - 1 : -1, x < w - 1 ? i + 1 : -1, y > 0 ? i - w : -1, y < h - 1 ? i + w : -1};
      for (int j : nb)
        if (j >= 0 && label[j] == -2) {
          label[j] = id;
          stack.push_back(j);
        }
    }
  }
  return out;
}

std::vector<PatchQuad> patch_quads(const RawImage& img, const RegionLabels& regions, const QuadOptions& options) {
  const int w = regions.width, h = regions.height, n = regions.count;
  struct Stats {
    long count = 0;
    int x0 = std::numeric_limits<int>::max(), x1 = -1, y0 = std::numeric_limits<int>::max(), y1 = -1;
    double sx = 0, sy = 0;
    Vec3 rgb = Vec3::Zero();
  };
  std::vector<Stats> st(n);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int l = regions.label[size_t(y) * w + x];
      if (l < 0) continue;
      Stats& s = st[l];
      ++s.count;
      s.x0 = std::min(s.x0, x);
      s.x1 = std::max(s.x1, x);
      s.y0 = std::min(s.y0, y);
      s.y1 = std::max(s.y1, y);
      s.sx += x + 0.5;
      s.sy += y + 0.5;
      for (int c = 0; c < 3; ++c) s.rgb[c] += img.at(x, y, c);
    }
  const double max_pixels = options.max_fraction * double(w) * h;
  std::vector<int> keep_index(n, -1);
  std::vector<std::vector<std::array<int, 2>>> rows;  // per kept region: x extent per row
  for (int l = 0; l < n; ++l) {
    const Stats& s = st[l];
    if (s.count < options.min_pixels || s.count > max_pixels) continue;
    if (s.x0 <= 1 || s.y0 <= 1 || s.x1 >= w - 2 || s.y1 >= h - 2) continue;  // touches the border
    keep_index[l] = static_cast<int>(rows.size());
    rows.emplace_back(size_t(s.y1 - s.y0 + 1), std::array<int, 2>{std::numeric_limits<int>::max(), -1});
  }
  std::vector<int> kept_label(rows.size());
  for (int l = 0; l < n; ++l)
    if (keep_index[l] >= 0) kept_label[keep_index[l]] = l;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int l = regions.label[size_t(y) * w + x];
      if (l < 0 || keep_index[l] < 0) continue;
      auto& e = rows[keep_index[l]][y - st[l].y0];
      e[0] = std::min(e[0], x);
      e[1] = std::max(e[1], x);
    }
  std::vector<PatchQuad> out;
  constexpr double kPi = 3.14159265358979323846;
  for (size_t k = 0; k < rows.size(); ++k) {
    const Stats& s = st[kept_label[k]];
    std::vector<Point> pts;
    pts.reserve(rows[k].size() * 4);
    for (size_t r = 0; r < rows[k].size(); ++r) {
      if (rows[k][r][1] < 0) continue;
      const double y = s.y0 + double(r);
      for (double yy : {y, y + 1}) {
        pts.emplace_back(rows[k][r][0], yy);
        pts.emplace_back(rows[k][r][1] + 1, yy);
      }
    }
    // Pixels between each row's extremes: holes left by noise inside a patch count as filled.
    double filled = 0;
    for (const auto& e : rows[k])
      if (e[1] >= 0) filled += e[1] - e[0] + 1;
    const std::vector<Point> hull = convex_hull(pts);
    if (hull.size() < 4) continue;
    const double hull_area = polygon_area(hull);
    // Largest quadrilateral of support points in four perpendicular directions.
    double best = -1;
    std::array<Point, 4> quad;
    for (int step = 0; step < 30; ++step) {
      const double psi = step * (kPi / 2) / 30;
      std::array<Point, 4> q;
      for (int d = 0; d < 4; ++d) {
        const Point dir(detmath::cos(psi + d * kPi / 2), detmath::sin(psi + d * kPi / 2));
        double m = -1e300;
        for (const Point& p : hull)
          if (p.dot(dir) > m) {
            m = p.dot(dir);
            q[d] = p;
          }
      }
      const double a = polygon_area({q[0], q[1], q[2], q[3]});
      if (a > best) {
        best = a;
        quad = q;
      }
    }
    if (!(best > 0) || best < 0.8 * hull_area || filled < 0.85 * best || filled > 1.15 * best) continue;
    // Shape: no sliver (interior angles 35-145°, adjacent sides within 1:4).
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
      const Point a = quad[(i + 3) % 4] - quad[i], b = quad[(i + 1) % 4] - quad[i];
      const double la = a.norm(), lb = b.norm();
      if (la < 1 || lb < 1 || la > 4 * lb || lb > 4 * la) ok = false;
      else if (std::abs(a.dot(b) / (la * lb)) > detmath::cos(35 * kPi / 180)) ok = false;
    }
    if (!ok) continue;
    PatchQuad pq;
    pq.corners = quad;
    pq.centre = Point(s.sx / s.count, s.sy / s.count);
    pq.side_a = ((quad[1] - quad[0]) + (quad[2] - quad[3])) / 2;
    pq.side_b = ((quad[3] - quad[0]) + (quad[2] - quad[1])) / 2;
    pq.area = filled;
    pq.mean = s.rgb / double(s.count);
    out.push_back(pq);
  }
  return out;
}

}  // namespace tristim

// Chart detection, steps 1-3: working image, flat regions, patch quadrilaterals (detect.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

// p-th percentile (0..1) of v (reorders v).
float percentile(std::vector<float>& v, double p) {
  if (v.empty()) return 0.f;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// 3×3 box mean of an interleaved 3-channel image (edges: the mean of the pixels inside).
std::vector<float> box3(const std::vector<float>& in, int w, int h) {
  std::vector<float> tmp(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int x0 = std::max(0, x - 1), x1 = std::min(w - 1, x + 1);
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int xx = x0; xx <= x1; ++xx) s += in[(size_t(y) * w + xx) * 3 + c];
        tmp[(size_t(y) * w + x) * 3 + c] = s / float(x1 - x0 + 1);
      }
    }
  for (int y = 0; y < h; ++y) {
    const int y0 = std::max(0, y - 1), y1 = std::min(h - 1, y + 1);
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int yy = y0; yy <= y1; ++yy) s += tmp[(size_t(yy) * w + x) * 3 + c];
        out[(size_t(y) * w + x) * 3 + c] = s / float(y1 - y0 + 1);
      }
  }
  return out;
}

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
  out.rgb.assign(size_t(out.width) * out.height * 3, 0.f);
  out.saturated.assign(size_t(out.width) * out.height, 0);
  const bool has_sat = image.saturated.size() == size_t(image.width) * image.height;
  const float norm = 1.f / float(f * f);
  for (int y = 0; y < out.height; ++y) {
    float* row = &out.rgb[size_t(y) * out.width * 3];
    for (int yy = y * f; yy < (y + 1) * f; ++yy) {
      const float* src = &image.rgb[size_t(yy) * image.width * 3];
      for (int x = 0; x < out.width; ++x) {
        float s0 = 0, s1 = 0, s2 = 0;
        for (int xx = x * f; xx < (x + 1) * f; ++xx) {
          s0 += src[xx * 3];
          s1 += src[xx * 3 + 1];
          s2 += src[xx * 3 + 2];
        }
        row[x * 3] += s0;
        row[x * 3 + 1] += s1;
        row[x * 3 + 2] += s2;
        if (has_sat)
          for (int xx = x * f; xx < (x + 1) * f; ++xx)
            out.saturated[size_t(y) * out.width + x] |= image.saturated[size_t(yy) * image.width + xx];
      }
    }
    for (int i = 0; i < out.width * 3; ++i) row[i] *= norm;
  }
  return out;
}

NoiseModel estimate_noise(const RawImage& img) {
  NoiseModel model;
  const int w = img.width, h = img.height;
  if (w < 8 || h < 8) return model;
  for (int c = 0; c < 3; ++c) {
    // d = I(x) - (I(x-1) + I(x+1)) / 2 has variance 1.5 σ² where the image is flat.
    std::vector<std::pair<float, float>> sd;
    sd.reserve(size_t(w) * h / 4);
    for (int y = 1; y < h - 1; y += 2)
      for (int x = 1; x < w - 1; x += 2) {
        const float i = img.at(x, y, c);
        sd.emplace_back(i, i - 0.5f * (img.at(x - 1, y, c) + img.at(x + 1, y, c)));
      }
    std::sort(sd.begin(), sd.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    // 24 bins of equal count: the median level and the MAD-based variance of each.
    constexpr int kBins = 24;
    Eigen::MatrixXd A(kBins, 2);
    Eigen::VectorXd b(kBins), wt(kBins);
    for (int k = 0; k < kBins; ++k) {
      const size_t lo = sd.size() * k / kBins, hi = sd.size() * (k + 1) / kBins;
      std::vector<float> level, dev;
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
  out.label.assign(size_t(w) * h, -1);
  if (w < 5 || h < 5) return out;
  const NoiseModel noise = estimate_noise(img);
  const std::vector<float> smooth = box3(img.rgb, w, h);
  // log(RGB + eps): ratio edges count the same in light and shade (vignetting, uneven light).
  std::vector<float> logs(smooth.size()), sigma(smooth.size());
  float eps[3];
  for (int c = 0; c < 3; ++c) {
    std::vector<float> v;
    v.reserve(smooth.size() / 3 / 7 + 1);
    for (size_t i = c; i < smooth.size(); i += 3 * 7) v.push_back(smooth[i]);
    eps[c] = std::max(1e-6f, 0.002f * percentile(v, 0.99));
  }
  // Noise of half a central difference of log(3×3 mean): σ(I)/3 · √2 / 2 / (I + eps).
  for (size_t i = 0; i < smooth.size(); ++i) {
    const int c = static_cast<int>(i % 3);
    const float v = std::max(0.f, smooth[i]) + eps[c];
    logs[i] = std::log(v);
    sigma[i] = static_cast<float>(std::sqrt(noise.gain[c] * std::max(0.f, smooth[i]) + noise.floor[c]) / 3 * 0.7071 / v);
  }
  // Flat: in every channel both half central differences stay below noise_multiple σ (and the
  // min_step floor).
  std::vector<std::uint8_t> flat(size_t(w) * h, 0);
  const float k = static_cast<float>(options.noise_multiple), floor = static_cast<float>(options.min_step);
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      const size_t i = size_t(y) * w + x;
      bool ok = true;
      for (int c = 0; c < 3 && ok; ++c) {
        const float g = 0.5f * std::max(std::abs(logs[(i + 1) * 3 + c] - logs[(i - 1) * 3 + c]),
                                        std::abs(logs[(i + w) * 3 + c] - logs[(i - w) * 3 + c]));
        ok = g < std::max(floor, k * sigma[i * 3 + c]);
      }
      flat[i] = ok;
    }
  // Erode once (3×3): thin bridges between neighbouring patches break.
  std::vector<std::uint8_t> core(flat.size(), 0);
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      bool all_flat = true;
      for (int dy = -1; dy <= 1 && all_flat; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (!flat[size_t(y + dy) * w + x + dx]) {
            all_flat = false;
            break;
          }
      core[size_t(y) * w + x] = all_flat;
    }
  // 4-connected components (explicit stack).
  std::vector<int> stack;
  for (size_t start = 0; start < core.size(); ++start) {
    if (!core[start] || out.label[start] >= 0) continue;
    const int id = out.count++;
    out.label[start] = id;
    stack.assign(1, static_cast<int>(start));
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int x = i % w, y = i / w;
      const int nb[4] = {x > 0 ? i - 1 : -1, x < w - 1 ? i + 1 : -1, y > 0 ? i - w : -1, y < h - 1 ? i + w : -1};
      for (int j : nb)
        if (j >= 0 && core[j] && out.label[j] < 0) {
          out.label[j] = id;
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
        const Point dir(std::cos(psi + d * kPi / 2), std::sin(psi + d * kPi / 2));
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
      else if (std::abs(a.dot(b) / (la * lb)) > std::cos(35 * kPi / 180)) ok = false;
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

// Chart detection, step 6: sub-pixel corners from the patch edges (detect.hpp).
//
// Each patch side facing a surround of another colour (the gap or frame, or the neighbouring
// patch when the layout has no gap) is measured at a few points along it: a profile across the
// edge, averaged along it, is projected onto the direction from the patch's colour to the
// surround's; the edge is where that projection crosses one half (the 50 % point of a blurred
// step). The corners (the homography of homography_unit_square) and, optionally, the gap are then
// fitted to every edge point by Gauss-Newton on point-to-edge-line distances with Huber weights.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

namespace tristim {

using Point = Eigen::Vector2d;

namespace {

// The layout's patch rectangles as a function of the gap (the grid() rule of layout.cpp).
struct GridModel {
  int R = 0, C = 0;
  double ml = 0, mt = 0, mr = 0, mb = 0;
  double w(double g) const { return (1 - ml - mr) / (C + (C - 1) * g); }
  double h(double g) const { return (1 - mt - mb) / (R + (R - 1) * g); }
  double u0(int c, double g) const { return ml + c * w(g) * (1 + g); }
  double v0(int r, double g) const { return mt + r * h(g) * (1 + g); }
};

struct EdgeObs {
  Point p;          // measured edge point, image pixels
  int axis = 0;     // 0: a vertical chart line u = const; 1: horizontal v = const
  int index = 0;    // column (axis 0) or row (axis 1)
  int side = 0;     // 0: the cell's leading edge (u0 / v0), 1: trailing (u1 / v1)
  int patch = 0;    // row-major patch index, side 0-3 (top, right, bottom, left)
  int patch_side = 0;
};

Eigen::Matrix3d H_of(const std::array<double, 8>& corners) {
  const auto h = homography_unit_square(corners);
  Eigen::Matrix3d H;
  H << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8];
  return H;
}

Vec3 bilinear(const RawImage& img, double x, double y) {
  // Pixel (i, j) has its centre at (i + 0.5, j + 0.5); clamp to the image.
  x = std::min(std::max(x - 0.5, 0.0), img.width - 1.0);
  y = std::min(std::max(y - 0.5, 0.0), img.height - 1.0);
  const int x0 = std::min(static_cast<int>(x), img.width - 2 < 0 ? 0 : img.width - 2);
  const int y0 = std::min(static_cast<int>(y), img.height - 2 < 0 ? 0 : img.height - 2);
  const int x1 = std::min(x0 + 1, img.width - 1), y1 = std::min(y0 + 1, img.height - 1);
  const double fx = x - x0, fy = y - y0;
  Vec3 v;
  for (int c = 0; c < 3; ++c)
    v[c] = (1 - fy) * ((1 - fx) * img.at(x0, y0, c) + fx * img.at(x1, y0, c)) +
           fy * ((1 - fx) * img.at(x0, y1, c) + fx * img.at(x1, y1, c));
  return v;
}

double edge_coordinate(const GridModel& m, const EdgeObs& o, double g) {
  return o.axis == 0 ? m.u0(o.index, g) + o.side * m.w(g) : m.v0(o.index, g) + o.side * m.h(g);
}

// Signed distance (px) of the edge point from the image of its chart line.
double residual(const GridModel& m, const Eigen::Matrix3d& H, double g, const EdgeObs& o) {
  const double a = edge_coordinate(m, o, g);
  const Point A = apply_homography(H, o.axis == 0 ? Point(a, 0) : Point(0, a));
  const Point B = apply_homography(H, o.axis == 0 ? Point(a, 1) : Point(1, a));
  const Point d = B - A, q = o.p - A;
  return (d.x() * q.y() - d.y() * q.x()) / (d.norm() + 1e-300);
}

Vec3 median3(std::vector<Vec3>& v) {
  Vec3 out = Vec3::Zero();
  if (v.empty()) return out;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> x;
    for (const auto& p : v) x.push_back(p[c]);
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    out[c] = x[x.size() / 2];
  }
  return out;
}

std::vector<EdgeObs> measure_edges(const RawImage& img, const GridModel& m, double g,
                                   const std::function<Point(double, double)>& at, double search) {
  const double w = m.w(g), h = m.h(g);
  auto inside = [&](const Point& p) { return p.x() >= 1 && p.y() >= 1 && p.x() <= img.width - 1 && p.y() <= img.height - 1; };
  // Patch colours: mean of a 7×7 grid over the central half of each patch.
  // Their spread (per channel standard deviation of the 49 samples) is the noise level.
  std::vector<Vec3> inner(size_t(m.R) * m.C, Vec3::Zero()), spread(inner.size(), Vec3::Zero());
  Vec3 scale = Vec3::Zero();
  for (int r = 0; r < m.R; ++r)
    for (int c = 0; c < m.C; ++c) {
      Vec3 s = Vec3::Zero(), s2 = Vec3::Zero();
      for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j) {
          const Point p = at(m.u0(c, g) + w * (0.25 + 0.5 * (i + 0.5) / 7), m.v0(r, g) + h * (0.25 + 0.5 * (j + 0.5) / 7));
          if (!inside(p)) continue;
          const Vec3 v = bilinear(img, p.x(), p.y());
          s += v;
          s2 += v.cwiseProduct(v);
        }
      inner[size_t(r) * m.C + c] = s / 49.0;
      spread[size_t(r) * m.C + c] = (s2 / 49.0 - (s / 49.0).cwiseProduct(s / 49.0)).cwiseMax(0.0).cwiseSqrt();
      scale += s / 49.0;
    }
  scale /= double(m.R * m.C);
  for (int c = 0; c < 3; ++c) scale[c] = std::max(scale[c], 1e-6 * scale.maxCoeff() + 1e-30);
  // Surround: beyond the grid (0.3 of a patch out) and, with a gap, the middle of the gaps.
  std::vector<Vec3> ring, gaps;
  for (int k = 0; k < 5 * std::max(m.R, m.C); ++k) {
    const double t = (k + 0.5) / (5 * std::max(m.R, m.C));
    for (const Point& uv : {Point(t, m.mt - 0.3 * h), Point(t, 1 - m.mb + 0.3 * h), Point(m.ml - 0.3 * w, t),
                            Point(1 - m.mr + 0.3 * w, t)}) {
      const Point p = at(uv.x(), uv.y());
      if (inside(p)) ring.push_back(bilinear(img, p.x(), p.y()));
    }
  }
  const double gap_px = g * std::min((at(w, 0.5) - at(0, 0.5)).norm(), (at(0.5, h) - at(0.5, 0)).norm());
  if (g > 0 && gap_px >= 3)
    for (int r = 0; r < m.R; ++r)
      for (int c = 0; c + 1 < m.C; ++c) {
        const Point p = at(m.u0(c, g) + w * (1 + g / 2), m.v0(r, g) + h / 2);
        if (inside(p)) gaps.push_back(bilinear(img, p.x(), p.y()));
      }
  const Vec3 ring_colour = median3(ring);
  const Vec3 gap_colour = gaps.size() >= 3 ? median3(gaps) : ring_colour;

  std::vector<EdgeObs> out;
  const double u_dir[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};  // outward: top, right, bottom, left
  for (int r = 0; r < m.R; ++r)
    for (int c = 0; c < m.C; ++c) {
      const Vec3 I = inner[size_t(r) * m.C + c];
      const double noise = spread[size_t(r) * m.C + c].cwiseQuotient(scale).norm();
      const double cu0 = m.u0(c, g), cv0 = m.v0(r, g);
      const Point centre = at(cu0 + w / 2, cv0 + h / 2);
      for (int s = 0; s < 4; ++s) {
        const int nr = r + static_cast<int>(u_dir[s][1]), nc = c + static_cast<int>(u_dir[s][0]);
        const bool outer = nr < 0 || nc < 0 || nr >= m.R || nc >= m.C;
        const Vec3 O = outer ? ring_colour : (g > 0 ? gap_colour : inner[size_t(nr) * m.C + nc]);
        const Vec3 d = (O - I).cwiseQuotient(scale);
        if (d.norm() < 0.03) continue;  // no visible edge
        // The side's end points in chart coordinates.
        Point a, b;
        if (s == 0) a = {cu0, cv0}, b = {cu0 + w, cv0};
        if (s == 1) a = {cu0 + w, cv0}, b = {cu0 + w, cv0 + h};
        if (s == 2) a = {cu0 + w, cv0 + h}, b = {cu0, cv0 + h};
        if (s == 3) a = {cu0, cv0 + h}, b = {cu0, cv0};
        const double side_px = (at(b.x(), b.y()) - at(a.x(), a.y())).norm();
        const double other_px = (s % 2 == 0) ? (at(cu0, cv0 + h) - at(cu0, cv0)).norm() : (at(cu0 + w, cv0) - at(cu0, cv0)).norm();
        const double S = std::min(search, 0.45 * other_px);
        if (S < 0.75) continue;
        // K measurements along the central 60 % of the side, each averaging a segment of it
        // (samples ~1 px apart) long enough for the edge to stand 4 σ out of the noise.
        const double needed = (4 * noise / d.norm()) * (4 * noise / d.norm());
        const int K = std::max(1, std::min({6, static_cast<int>(side_px / 10), static_cast<int>(0.6 * side_px / std::max(needed, 5.0))}));
        const double L = 0.3 * side_px / K;
        const int msamples = std::max(2, std::min(24, static_cast<int>(2 * L)));
        if (d.norm() < 4 * noise / std::sqrt(double(msamples))) continue;
        const double ds = std::max(0.25, 2 * S / 64);
        const int ns = static_cast<int>(2 * S / ds) + 1;
        for (int j = 0; j < K; ++j) {
          const double t = 0.2 + 0.6 * (j + 0.5) / K;
          const Point uv = a + t * (b - a);
          const Point p = at(uv.x(), uv.y());
          Point T = at(uv.x() + 1e-3 * (b - a).x(), uv.y() + 1e-3 * (b - a).y()) - p;
          T.normalize();
          Point N(-T.y(), T.x());
          if (N.dot(p - centre) < 0) N = -N;
          if (!inside(p - S * N - L * T) || !inside(p + S * N + L * T) || !inside(p - S * N + L * T) ||
              !inside(p + S * N - L * T))
            continue;
          std::vector<double> f(ns);
          for (int i = 0; i < ns; ++i) {
            const double sv = -S + i * ds;
            Vec3 x = Vec3::Zero();
            for (int k = 0; k < msamples; ++k) {
              const double o = msamples == 1 ? 0 : -L + 2 * L * k / (msamples - 1);
              const Point q = p + sv * N + o * T;
              x += bilinear(img, q.x(), q.y());
            }
            x /= double(msamples);
            f[i] = (x - I).cwiseQuotient(scale).dot(d) / d.squaredNorm();
          }
          if (f[0] > 0.3) continue;  // the profile does not start inside the patch
          int cross = -1;
          for (int i = 1; i < ns; ++i)
            if (f[i] >= 0.5) {
              cross = i;
              break;
            }
          if (cross < 0 || cross == ns - 1) continue;
          double fmax = 0;
          for (int i = cross; i < ns; ++i) fmax = std::max(fmax, f[i]);
          if (fmax < 0.7) continue;
          const double s0 = -S + (cross - 1) * ds;
          const double sx = s0 + ds * (0.5 - f[cross - 1]) / (f[cross] - f[cross - 1]);
          EdgeObs o;
          o.p = p + sx * N;
          o.axis = (s % 2 == 1) ? 0 : 1;  // left/right sides are vertical chart lines
          o.index = o.axis == 0 ? c : r;
          o.side = (s == 1 || s == 2) ? 1 : 0;
          o.patch = r * m.C + c;
          o.patch_side = s;
          out.push_back(o);
        }
      }
    }
  return out;
}

// The fitted model: the corners of the patch grid and the gap.
struct GridState {
  std::array<double, 8> corners{};
  double gap = 0;
};

struct FitResult {
  GridState state;
  double rms = 0;
  int inliers = 0;
};

// Robust Gauss-Newton (Levenberg-Marquardt damping, Huber weights at 1.5 MAD-σ) over the
// corners and, when free, the gap.
FitResult fit_edges(const GridModel& m, const std::vector<EdgeObs>& obs, const GridState& start, bool fit_gap) {
  std::vector<int> free = {0, 1, 2, 3, 4, 5, 6, 7};
  if (fit_gap) free.push_back(8);
  const int P = static_cast<int>(free.size());
  auto unpack = [&](const Eigen::VectorXd& th) {
    GridState s = start;
    for (int i = 0; i < P; ++i) {
      if (free[i] < 8) s.corners[free[i]] = th[i];
      else s.gap = std::min(std::max(th[i], 0.0), 1.5);
    }
    return s;
  };
  Eigen::VectorXd theta(P);
  for (int i = 0; i < P; ++i) theta[i] = free[i] < 8 ? start.corners[free[i]] : start.gap;
  auto residuals = [&](const Eigen::VectorXd& th) {
    const GridState s = unpack(th);
    const Eigen::Matrix3d H = H_of(s.corners);
    Eigen::VectorXd r(obs.size());
    for (size_t i = 0; i < obs.size(); ++i) r[i] = residual(m, H, s.gap, obs[i]);
    return r;
  };
  Eigen::VectorXd r = residuals(theta), wts = Eigen::VectorXd::Ones(r.size());
  double sigma = 1, lambda = 1e-3;
  const size_t n = obs.size();
  for (int it = 0; it < 20; ++it) {
    std::vector<double> a(n);
    for (size_t i = 0; i < n; ++i) a[i] = std::abs(r[i]);
    std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
    sigma = std::max(0.05, 1.4826 * a[a.size() / 2]);
    for (size_t i = 0; i < n; ++i) wts[i] = std::abs(r[i]) <= 1.5 * sigma ? 1.0 : 1.5 * sigma / std::abs(r[i]);
    Eigen::MatrixXd J(r.size(), P);
    for (int k = 0; k < P; ++k) {
      const double step = free[k] < 8 ? 1e-3 : 1e-5;
      Eigen::VectorXd tp = theta, tm = theta;
      tp[k] += step;
      tm[k] -= step;
      J.col(k) = (residuals(tp) - residuals(tm)) / (2 * step);
    }
    const Eigen::MatrixXd JtW = J.transpose() * wts.asDiagonal();
    const Eigen::MatrixXd A = JtW * J;
    const Eigen::VectorXd grad = JtW * r;
    const double cost = r.dot(wts.asDiagonal() * r);
    bool improved = false;
    Eigen::VectorXd delta;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Eigen::MatrixXd Ad = A;
      Ad.diagonal() += lambda * A.diagonal().cwiseMax(1e-12);
      delta = -Ad.ldlt().solve(grad);
      const Eigen::VectorXd cand = theta + delta;
      const Eigen::VectorXd rc = residuals(cand);
      if (rc.allFinite() && rc.dot(wts.asDiagonal() * rc) <= cost) {
        theta = cand;
        r = rc;
        improved = true;
        lambda = std::max(1e-7, lambda / 10);
      } else {
        lambda *= 10;
      }
    }
    if (!improved || delta.head(8).cwiseAbs().maxCoeff() < 1e-4) break;
  }
  FitResult out;
  out.state = unpack(theta);
  double ss = 0;
  for (size_t i = 0; i < n; ++i)
    if (std::abs(r[i]) < 3 * sigma) {
      ss += r[i] * r[i];
      ++out.inliers;
    }
  out.rms = out.inliers ? std::sqrt(ss / out.inliers) : 0;
  return out;
}

}  // namespace

Refinement refine_corners(const RawImage& image, const LayoutOptions& lo, const std::array<double, 8>& corners,
                          double search_px, bool fit_gap) {
  const ChartLayout layout = chart_layout(lo);
  GridModel m;
  m.R = layout.rows;
  m.C = layout.columns;
  if (lo.chart == "custom") {
    m.ml = lo.margin_left;
    m.mt = lo.margin_top;
    m.mr = lo.margin_right;
    m.mb = lo.margin_bottom;
  }
  GridState state;
  state.corners = corners;
  state.gap = layout.gap;
  Refinement out;
  out.corners = corners;
  out.gap = layout.gap;
  double search = search_px;
  for (int round = 0; round < 4; ++round) {
    const Eigen::Matrix3d H = H_of(state.corners);
    const auto map = [&](double u, double v) { return apply_homography(H, Point(u, v)); };
    const std::vector<EdgeObs> obs = measure_edges(image, m, state.gap, map, search);
    if (obs.size() < 8) break;
    int inner_edges = 0;  // edges that tell the gap from the scale: not on the grid's outline
    for (const auto& o : obs)
      inner_edges += !((o.side == 0 && o.index == 0) || (o.side == 1 && o.index == (o.axis == 0 ? m.C : m.R) - 1));
    const bool with_gap = fit_gap && layout.gap > 0 && inner_edges >= 8;
    const FitResult f = fit_edges(m, obs, state, with_gap);
    double moved = 0;
    for (int i = 0; i < 8; ++i) moved = std::max(moved, std::abs(f.state.corners[i] - state.corners[i]));
    state = f.state;
    out.corners = f.state.corners;
    out.gap = f.state.gap;
    out.rms = f.rms;
    out.edges = static_cast<int>(obs.size());
    out.inliers = f.inliers;
    std::vector<int> sides(size_t(m.R) * m.C, 0);
    for (const auto& o : obs) sides[o.patch] |= 1 << o.patch_side;
    int supported = 0;
    for (int bits : sides) supported += ((bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1) + ((bits >> 3) & 1)) >= 2;
    out.supported = double(supported) / sides.size();
    search = std::max(1.0, std::min(search, 3 * f.rms + 1.0));
    if (moved < 0.02) break;
  }
  return out;
}

}  // namespace tristim

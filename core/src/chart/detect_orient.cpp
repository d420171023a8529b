// Chart detection, steps 5 and 7: placing the layout on a lattice (rotation, mirror, offset) by
// the residual of a quick 3×3 fit to the reference colours (detect.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "../detmath.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

namespace tristim {

using Point = Eigen::Vector2d;

namespace {

constexpr double kLn2 = 0x1.62e42fefa39efp-1;  // ln 2 rounded to double

// Weighted least squares M (3×3) with camera ≈ M · reference, weights per pair.
// The sums of w·ref·refᵀ and w·ref·rgbᵀ are kept in scalars: each term is (w·ref_i)·x_j, added in
// the order of k, as with Eigen's outer products, but without a round trip through memory per term.
Mat3 fit_matrix(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const std::vector<double>& weight) {
  double a[3][3] = {}, b[3][3] = {};
  for (size_t k = 0; k < rgb.size(); ++k) {
    const double wr[3] = {weight[k] * ref[k][0], weight[k] * ref[k][1], weight[k] * ref[k][2]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        a[i][j] += wr[i] * ref[k][j];
        b[i][j] += wr[i] * rgb[k][j];
      }
  }
  Mat3 AtA, AtB;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) AtA(i, j) = a[i][j], AtB(i, j) = b[i][j];
  AtA += 1e-12 * AtA.trace() * Mat3::Identity();
  return (AtA.ldlt().solve(AtB)).transpose();
}

std::vector<double> relative_residuals(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const Mat3& M) {
  double brightest = 0;
  for (const auto& r : ref) brightest = std::max(brightest, (M * r).norm());
  const double floor = 0.02 * brightest + 1e-30;
  std::vector<double> e(rgb.size());
  for (size_t k = 0; k < rgb.size(); ++k) {
    const Vec3 p = M * ref[k];
    e[k] = (rgb[k] - p).norm() / (p.norm() + floor);
  }
  return e;
}

// Mean of the smallest 75 % of the residuals.
double trimmed_mean(std::vector<double> e) {
  const size_t keep = std::max<size_t>(1, static_cast<size_t>(std::ceil(0.75 * e.size())));
  std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(keep - 1), e.end());
  std::sort(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(keep));  // summed in increasing order, as before
  return std::accumulate(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(keep), 0.0) / double(keep);
}

// The 8 symmetries of the square acting on (c, r): 0-3 rotations by 90° steps, 4-7 the same
// after the mirror c -> -c.
std::array<int, 2> dihedral(int t, int c, int r) {
  if (t >= 4) c = -c;
  switch (t % 4) {
    case 0: return {c, r};
    case 1: return {-r, c};
    case 2: return {-c, -r};
    default: return {r, -c};
  }
}

}  // namespace

std::vector<double> reference_fit_residuals(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref,
                                            const std::vector<Eigen::Vector2d>& positions) {
  const size_t n = rgb.size();
  if (ref.size() != n || n < 4 || (!positions.empty() && positions.size() != n))
    throw Error(ErrorCode::InvalidArgument, "the 3x3 reference fit needs 4 or more camera/reference pairs");
  // Relative errors: weight 1/|ref|² (the camera scale is unknown, the reference sets the level).
  double brightest = 0;
  for (const auto& r : ref) brightest = std::max(brightest, r.squaredNorm());
  std::vector<double> w0(n), w(n);
  for (size_t k = 0; k < n; ++k) w0[k] = w[k] = 1.0 / (ref[k].squaredNorm() + 4e-4 * brightest + 1e-30);
  // Light across the chart: log L = β · (1, u, v[, u², v², uv]) (linear from 12 patches,
  // quadratic from 24), each factor within 0.5..2 of 1.
  const int terms = positions.empty() || n < 12 ? 0 : n < 24 ? 3 : 6;
  std::vector<double> light(n, 1.0);
  std::vector<Vec3> lit = ref;
  std::vector<double> e, sorted;
  const int iterations = terms ? 4 : 2;
  for (int it = 0; it < iterations; ++it) {
    for (size_t k = 0; k < n; ++k) lit[k] = light[k] * ref[k];
    const Mat3 M = fit_matrix(rgb, lit, w);
    e = relative_residuals(rgb, lit, M);
    if (it == iterations - 1) break;  // the weights and light below would only serve a next fit
    // Refit without the worst 25 % (glare, a shadow, a missing patch).
    sorted = e;
    const auto q3 = sorted.begin() + static_cast<std::ptrdiff_t>(std::floor(0.75 * (sorted.size() - 1)));
    std::nth_element(sorted.begin(), q3, sorted.end());
    const double cut = *q3;
    for (size_t k = 0; k < n; ++k) w[k] = e[k] > cut ? 0 : w0[k];
    if (!terms) continue;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), terms);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    for (size_t k = 0; k < n; ++k) {
      const Vec3 p = M * ref[k];
      const double rho = rgb[k].dot(p) / (p.squaredNorm() + 1e-300);
      if (!(w[k] > 0) || !(rho > 0) || p.squaredNorm() < 4e-3 * brightest * M.squaredNorm() / 3) continue;
      const double u = positions[k].x() - 0.5, v = positions[k].y() - 0.5;
      const double phi[6] = {1, u, v, u * u, v * v, u * v};
      for (int j = 0; j < terms; ++j) A(static_cast<Eigen::Index>(k), j) = phi[j];
      b(static_cast<Eigen::Index>(k)) = detmath::log(rho);
    }
    const Eigen::VectorXd beta = A.colPivHouseholderQr().solve(b);
    for (size_t k = 0; k < n; ++k) {
      const double u = positions[k].x() - 0.5, v = positions[k].y() - 0.5;
      const double phi[6] = {0, u, v, u * u, v * v, u * v};  // the constant stays in M
      double l = 0;
      for (int j = 1; j < terms; ++j) l += beta(j) * phi[j];
      light[k] = detmath::exp(std::min(kLn2, std::max(-kLn2, l)));
    }
  }
  return e;
}

double reference_fit_score(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref,
                           const std::vector<Eigen::Vector2d>& positions) {
  return trimmed_mean(reference_fit_residuals(rgb, ref, positions));
}

std::vector<Placement> place_layout(const RawImage& img, const GridGroup& group, const ChartLayout& layout,
                                    const std::vector<Vec3>& reference) {
  const int R = layout.rows, C = layout.columns;
  const int N = R * C;
  if (!reference.empty() && static_cast<int>(reference.size()) != N)
    throw Error(ErrorCode::InvalidArgument, "reference colours: " + std::to_string(reference.size()) +
                                                " for a layout of " + std::to_string(N) + " patches");
  const Eigen::Matrix3d& H = group.lattice_to_image;
  std::map<std::array<int, 2>, int> found;
  for (const auto& cell : group.cells) found[cell] = 1;
  // Mean RGB of the central part of a lattice cell (a square of ±20 % of the local pitch);
  // false when it leaves the image. Cached in a dense table: placements share cells, and every
  // cell they reach lies within max(R, C) - 1 cells of the group's range.
  const int reach = std::max(R, C);
  const int cache_p0 = group.p_min - reach, cache_q0 = group.q_min - reach;
  const int cache_w = group.p_max - group.p_min + 1 + 2 * reach, cache_h = group.q_max - group.q_min + 1 + 2 * reach;
  std::vector<std::pair<bool, Vec3>> cache(size_t(cache_w) * cache_h);
  std::vector<char> cached(cache.size(), 0);
  auto sample = [&](const std::array<int, 2>& cell) -> const std::pair<bool, Vec3>& {
    const size_t slot = size_t(cell[1] - cache_q0) * cache_w + size_t(cell[0] - cache_p0);
    if (cached[slot]) return cache[slot];
    const Point c = apply_homography(H, Point(cell[0], cell[1]));
    const double pitch = std::min((apply_homography(H, Point(cell[0] + 1, cell[1])) - c).norm(),
                                  (apply_homography(H, Point(cell[0], cell[1] + 1)) - c).norm());
    const double r = std::max(0.5, 0.2 * pitch);
    const int x0 = static_cast<int>(std::floor(c.x() - r)), x1 = static_cast<int>(std::ceil(c.x() + r));
    const int y0 = static_cast<int>(std::floor(c.y() - r)), y1 = static_cast<int>(std::ceil(c.y() + r));
    std::pair<bool, Vec3> s{false, Vec3::Zero()};
    if (std::isfinite(c.x()) && std::isfinite(c.y()) && x0 >= 0 && y0 >= 0 && x1 < img.width && y1 < img.height) {
      s.first = true;
      int n = 0;
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x, ++n)
          for (int k = 0; k < 3; ++k) s.second[k] += img.at(x, y, k);
      s.second /= double(std::max(1, n));
    }
    cached[slot] = 1;
    return cache[slot] = s;
  };
  // Chart unit square -> layout (column, row) coordinates of the cell centres (affine).
  const PatchCell& first = layout.patches.front();
  const double pw = (first.u1 - first.u0) * (1 + layout.gap), ph = (first.v1 - first.v0) * (1 + layout.gap);
  const double uc0 = (first.u0 + first.u1) / 2, vc0 = (first.v0 + first.v1) / 2;
  std::vector<Placement> out;
  for (int t = 0; t < 8; ++t) {
    int pa = 1 << 30, pb = -(1 << 30), qa = 1 << 30, qb = -(1 << 30);
    for (int c : {0, C - 1})
      for (int r : {0, R - 1}) {
        const auto pq = dihedral(t, c, r);
        pa = std::min(pa, pq[0]);
        pb = std::max(pb, pq[0]);
        qa = std::min(qa, pq[1]);
        qb = std::max(qb, pq[1]);
      }
    for (int op = group.p_min - pb; op <= group.p_max - pa; ++op)
      for (int oq = group.q_min - qb; oq <= group.q_max - qa; ++oq) {
        int covered = 0;
        for (const auto& cell : group.cells)
          covered += cell[0] >= pa + op && cell[0] <= pb + op && cell[1] >= qa + oq && cell[1] <= qb + oq;
        if (2 * covered < static_cast<int>(group.cells.size())) continue;
        Placement pl;
        pl.transform = t;
        pl.offset = {op, oq};
        pl.found = covered;
        std::vector<Vec3> rgb, ref;
        std::vector<Point> where;
        int outside = 0;
        for (int k = 0; k < N; ++k) {
          const auto& cell = layout.patches[k];
          const auto pq = dihedral(t, cell.column, cell.row);
          const auto& s = sample({pq[0] + op, pq[1] + oq});
          if (!s.first) {
            ++outside;
            continue;
          }
          rgb.push_back(s.second);
          where.emplace_back(C > 1 ? cell.column / (C - 1.0) : 0.5, R > 1 ? cell.row / (R - 1.0) : 0.5);
          if (!reference.empty()) ref.push_back(reference[k]);
        }
        pl.inside = outside == 0;
        if (rgb.size() < std::max<size_t>(6, N / 2)) continue;
        pl.residual = reference.empty() ? 0.0 : reference_fit_score(rgb, ref, where);
        // Corners: chart (u, v) -> layout (c, r) -> lattice -> image.
        const double us[4] = {0, 1, 1, 0}, vs[4] = {0, 0, 1, 1};
        std::vector<Point> k(4);
        for (int i = 0; i < 4; ++i) {
          const double c = (us[i] - uc0) / pw, r = (vs[i] - vc0) / ph;
          // dihedral() is linear: apply it to the continuous coordinates through its basis.
          const auto e1 = dihedral(t, 1, 0), e2 = dihedral(t, 0, 1);
          const Point l(c * e1[0] + r * e2[0] + op, c * e1[1] + r * e2[1] + oq);
          k[i] = apply_homography(H, l);
          pl.corners[2 * i] = k[i].x();
          pl.corners[2 * i + 1] = k[i].y();
        }
        double area2 = 0;
        for (int i = 0; i < 4; ++i) area2 += k[i].x() * k[(i + 1) % 4].y() - k[(i + 1) % 4].x() * k[i].y();
        pl.mirrored = area2 < 0;
        out.push_back(pl);
      }
  }
  std::stable_sort(out.begin(), out.end(), [](const Placement& a, const Placement& b) { return a.residual < b.residual; });
  return out;
}

}  // namespace tristim

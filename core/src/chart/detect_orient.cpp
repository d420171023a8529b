// Chart detection, steps 5 and 7: placing the layout on a lattice (rotation, mirror, offset) by
// the residual of a quick 3×3 fit to the reference colours (detect.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

namespace tristim {

using Point = Eigen::Vector2d;

namespace {

// Weighted least squares M (3×3) with camera ≈ M · reference, weights per pair.
Mat3 fit_matrix(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const std::vector<double>& weight) {
  Mat3 AtA = Mat3::Zero(), AtB = Mat3::Zero();
  for (size_t k = 0; k < rgb.size(); ++k) {
    AtA += weight[k] * ref[k] * ref[k].transpose();
    AtB += weight[k] * ref[k] * rgb[k].transpose();
  }
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

// Mean of the smallest 85 % of the residuals.
double trimmed_mean(std::vector<double> e) {
  std::sort(e.begin(), e.end());
  const size_t keep = std::max<size_t>(1, static_cast<size_t>(std::ceil(0.85 * e.size())));
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

std::vector<double> reference_fit_residuals(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref) {
  if (rgb.size() != ref.size() || rgb.size() < 4)
    throw Error(ErrorCode::InvalidArgument, "the 3x3 reference fit needs 4 or more camera/reference pairs");
  // Relative errors: weight 1/|ref|² (the camera scale is unknown, the reference sets the level).
  double brightest = 0;
  for (const auto& r : ref) brightest = std::max(brightest, r.squaredNorm());
  std::vector<double> w(rgb.size());
  for (size_t k = 0; k < rgb.size(); ++k) w[k] = 1.0 / (ref[k].squaredNorm() + 4e-4 * brightest + 1e-30);
  Mat3 M = fit_matrix(rgb, ref, w);
  std::vector<double> e = relative_residuals(rgb, ref, M);
  // Refit without the worst 15 % (glare, a shadow, a missing patch).
  std::vector<double> sorted = e;
  std::sort(sorted.begin(), sorted.end());
  const double cut = sorted[static_cast<size_t>(std::floor(0.85 * (sorted.size() - 1)))];
  for (size_t k = 0; k < e.size(); ++k)
    if (e[k] > cut) w[k] = 0;
  M = fit_matrix(rgb, ref, w);
  return relative_residuals(rgb, ref, M);
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
  // false when it leaves the image. Cached: placements share cells.
  std::map<std::array<int, 2>, std::pair<bool, Vec3>> cache;
  auto sample = [&](const std::array<int, 2>& cell) -> const std::pair<bool, Vec3>& {
    auto it = cache.find(cell);
    if (it != cache.end()) return it->second;
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
    return cache.emplace(cell, s).first->second;
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
          if (!reference.empty()) ref.push_back(reference[k]);
        }
        pl.inside = outside == 0;
        if (rgb.size() < std::max<size_t>(6, N / 2)) continue;
        pl.residual = reference.empty() ? 0.0 : trimmed_mean(reference_fit_residuals(rgb, ref));
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

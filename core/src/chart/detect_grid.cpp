// Chart detection, step 4: lattices of equal-pitch patch quads (detect.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "tristim/chart/detect.hpp"
#include "tristim/error.hpp"

namespace tristim {

using Point = Eigen::Vector2d;

Eigen::Matrix3d fit_homography(const std::vector<Point>& src, const std::vector<Point>& dst) {
  const size_t n = src.size();
  if (n < 4 || dst.size() != n) throw Error(ErrorCode::InvalidArgument, "a homography needs 4 or more point pairs");
  // Hartley normalisation of both point sets: centroid 0, mean distance sqrt(2).
  auto normaliser = [](const std::vector<Point>& p) {
    Point c = Point::Zero();
    for (const auto& q : p) c += q;
    c /= double(p.size());
    double d = 0;
    for (const auto& q : p) d += (q - c).norm();
    d /= double(p.size());
    const double s = d > 0 ? std::sqrt(2.0) / d : 1.0;
    Eigen::Matrix3d T;
    T << s, 0, -s * c.x(), 0, s, -s * c.y(), 0, 0, 1;
    return T;
  };
  const Eigen::Matrix3d Ts = normaliser(src), Td = normaliser(dst);
  Eigen::MatrixXd A(2 * n, 9);
  for (size_t i = 0; i < n; ++i) {
    const Point u = apply_homography(Ts, src[i]), x = apply_homography(Td, dst[i]);
    A.row(2 * i) << -u.x(), -u.y(), -1, 0, 0, 0, x.x() * u.x(), x.x() * u.y(), x.x();
    A.row(2 * i + 1) << 0, 0, 0, -u.x(), -u.y(), -1, x.y() * u.x(), x.y() * u.y(), x.y();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd h = svd.matrixV().col(8);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  Eigen::Matrix3d H = Td.inverse() * Hn * Ts;
  return H / H(2, 2);
}

namespace {

// Affine least squares lattice -> image (3 or more non-collinear cells), as a homography.
Eigen::Matrix3d fit_affine(const std::vector<Point>& src, const std::vector<Point>& dst) {
  Eigen::MatrixXd A(src.size(), 3);
  Eigen::MatrixXd B(src.size(), 2);
  for (size_t i = 0; i < src.size(); ++i) {
    A.row(i) << src[i].x(), src[i].y(), 1;
    B.row(i) << dst[i].x(), dst[i].y();
  }
  const Eigen::MatrixXd X = A.colPivHouseholderQr().solve(B);  // 3 x 2
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
  H.block<2, 3>(0, 0) = X.transpose();
  return H;
}

struct Growth {
  std::map<std::array<int, 2>, int> cell_quad;  // lattice cell -> quad
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
};

// Refits the lattice -> image map to the members' centres: a homography once both axes have
// 3+ distinct values and 6+ members, an affine map before. `two_rows`: a homography already from
// 6+ members on two rows (or columns) of 3+ — the DLT is well posed there too (no three of four
// points collinear), and under strong perspective the pitch changes from one cell to the next by
// more than an affine map can follow (a Classic tilted 49°: a third from one column to the next).
// `centre(m)`: the image point of member m (a quad's or a flat region's centre).
template <class Centre>
void refit(Growth& g, const Centre& centre, bool two_rows = false) {
  std::vector<Point> src, dst;
  std::set<int> ps, qs;
  for (const auto& kv : g.cell_quad) {
    src.emplace_back(kv.first[0], kv.first[1]);
    dst.push_back(centre(kv.second));
    ps.insert(kv.first[0]);
    qs.insert(kv.first[1]);
  }
  if (ps.size() < 2 || qs.size() < 2) return;
  if (src.size() >= 6 && ((ps.size() >= 3 && qs.size() >= 3) || (two_rows && (ps.size() >= 3 || qs.size() >= 3))))
    g.H = fit_homography(src, dst);
  else if (src.size() >= 3) g.H = fit_affine(src, dst);
}

// Area in the image of the lattice cell centred on `cell` (the parallelogram of the map's
// derivatives there: a homography's local scale), px².
double cell_area(const Eigen::Matrix3d& H, const std::array<int, 2>& cell) {
  const Point c(cell[0], cell[1]);
  const Point P = apply_homography(H, c + Point(0.5, 0)) - apply_homography(H, c - Point(0.5, 0));
  const Point Q = apply_homography(H, c + Point(0, 0.5)) - apply_homography(H, c - Point(0, 0.5));
  return std::abs(P.x() * Q.y() - P.y() * Q.x()) + 1e-12;
}

// Whether the members lie on exactly two rows or two columns (and 3+ of the other).
bool on_two_rows(const Growth& g) {
  std::set<int> ps, qs;
  for (const auto& kv : g.cell_quad) ps.insert(kv.first[0]), qs.insert(kv.first[1]);
  return (ps.size() == 2 && qs.size() >= 3) || (qs.size() == 2 && ps.size() >= 3);
}

// The lattice as a GridGroup (`quad_of(m)`: the quad index of member m, or -1); false when it
// has fewer than `min_cells` members or lies on one row or column.
template <class QuadOf>
bool to_group(const Growth& g, int min_cells, const QuadOf& quad_of, GridGroup& group) {
  std::set<int> ps, qs;
  for (const auto& kv : g.cell_quad) {
    ps.insert(kv.first[0]);
    qs.insert(kv.first[1]);
  }
  if (static_cast<int>(g.cell_quad.size()) < min_cells || ps.size() < 2 || qs.size() < 2) return false;
  group.lattice_to_image = g.H;
  group.p_min = *ps.begin();
  group.p_max = *ps.rbegin();
  group.q_min = *qs.begin();
  group.q_max = *qs.rbegin();
  for (const auto& kv : g.cell_quad) {
    group.cells.push_back(kv.first);
    group.quads.push_back(quad_of(kv.second));
  }
  return true;
}

// |cos| of the angle between two vectors.
double parallel(const Point& a, const Point& b) { return std::abs(a.dot(b)) / (a.norm() * b.norm() + 1e-12); }

}  // namespace

std::vector<GridGroup> group_grids(const std::vector<PatchQuad>& quads, int min_cells) {
  const int n = static_cast<int>(quads.size());
  const auto centre = [&](int j) { return quads[j].centre; };
  // Neighbour lists: centres within 2.8 patch sizes, areas within a factor 2.2 (sweep over x).
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return quads[a].centre.x() < quads[b].centre.x(); });
  std::vector<double> reach(n);
  double max_reach = 0;
  for (int i = 0; i < n; ++i) {
    reach[i] = 2.8 * std::max(quads[i].side_a.norm(), quads[i].side_b.norm());
    max_reach = std::max(max_reach, reach[i]);
  }
  std::vector<std::vector<int>> near(n);
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const int i = order[a], j = order[b];
      if (quads[j].centre.x() - quads[i].centre.x() > max_reach) break;
      const double d = (quads[j].centre - quads[i].centre).norm();
      const double ratio = quads[i].area / quads[j].area;
      if (ratio > 2.2 || ratio < 1 / 2.2) continue;
      if (d < std::max(reach[i], reach[j])) {
        near[i].push_back(j);
        near[j].push_back(i);
      }
    }
  // Axis neighbours in a quad's own frame: d = alpha·side_a + beta·side_b.
  struct Seed {
    int quad, score;
    Point P, Q;  // pitch vectors along side_a and side_b
  };
  std::vector<Seed> seeds;
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix2d B;
    B.col(0) = quads[i].side_a;
    B.col(1) = quads[i].side_b;
    if (std::abs(B.determinant()) < 1e-9) continue;
    const Eigen::Matrix2d Bi = B.inverse();
    bool dir[4] = {false, false, false, false};
    Point P(0, 0), Q(0, 0);
    double bestP = 1e9, bestQ = 1e9;
    for (int j : near[i]) {
      const Point d = quads[j].centre - quads[i].centre;
      const Point ab = Bi * d;
      for (int axis = 0; axis < 2; ++axis) {
        const double along = ab[axis], across = ab[1 - axis];
        if (std::abs(along) < 0.9 || std::abs(along) > 2.6 || std::abs(across) > 0.2 * std::abs(along) + 0.15) continue;
        dir[axis * 2 + (along > 0 ? 0 : 1)] = true;
        const Point step = along > 0 ? d : Point(-d);
        if (axis == 0 && std::abs(along) < bestP) {
          bestP = std::abs(along);
          P = step;
        }
        if (axis == 1 && std::abs(along) < bestQ) {
          bestQ = std::abs(along);
          Q = step;
        }
      }
    }
    // A seed is a single patch when its sides fill similar fractions of both pitches (a blob of
    // two merged patches does not); rank those first, then by the neighbours seen.
    int score = dir[0] + dir[1] + dir[2] + dir[3];
    if (bestP < 1e9 && bestQ < 1e9 && std::max(bestP, bestQ) < 1.3 * std::min(bestP, bestQ)) score += 4;
    if ((dir[0] || dir[1]) && (dir[2] || dir[3])) seeds.push_back({i, score, P, Q});
  }
  std::stable_sort(seeds.begin(), seeds.end(), [&](const Seed& a, const Seed& b) { return a.score > b.score; });

  std::vector<char> used(n, 0);
  std::vector<GridGroup> groups;
  for (const Seed& seed : seeds) {
    if (used[seed.quad]) continue;
    Growth g;
    g.cell_quad[{0, 0}] = seed.quad;
    g.H << seed.P.x(), seed.Q.x(), quads[seed.quad].centre.x(), seed.P.y(), seed.Q.y(), quads[seed.quad].centre.y(), 0, 0, 1;
    std::set<int> members = {seed.quad};
    bool two_rows = false;
    size_t stalled_at = 0;
    Eigen::Matrix3d stalled_H = g.H;
    for (int round = 0; round < 400; ++round) {
      const Eigen::Matrix3d Hi = g.H.inverse();
      std::vector<double> areas;
      for (int m : members) areas.push_back(quads[m].area);
      std::nth_element(areas.begin(), areas.begin() + areas.size() / 2, areas.end());
      const double median_area = areas[areas.size() / 2];
      // On two rows in perspective the patches grow or shrink from cell to cell: a member fills
      // a fraction of its cell's image (median), and a candidate is held to that fraction of its
      // own cell's image under the homography.
      double fill = 0;
      if (two_rows) {
        std::vector<double> fills;
        for (const auto& kv : g.cell_quad) fills.push_back(quads[kv.second].area / cell_area(g.H, kv.first));
        std::nth_element(fills.begin(), fills.begin() + fills.size() / 2, fills.end());
        fill = fills[fills.size() / 2];
      }
      std::map<std::array<int, 2>, std::pair<double, int>> offers;  // cell -> (residual, quad)
      std::set<int> pool;
      for (int m : members)
        for (int j : near[m])
          if (!used[j] && !members.count(j)) pool.insert(j);
      for (int j : pool) {
        const Point l = apply_homography(Hi, quads[j].centre);
        const std::array<int, 2> cell = {static_cast<int>(std::lround(l.x())), static_cast<int>(std::lround(l.y()))};
        const double res = std::abs(l.x() - cell[0]) + std::abs(l.y() - cell[1]);
        if (std::abs(l.x() - cell[0]) > 0.3 || std::abs(l.y() - cell[1]) > 0.3 || g.cell_quad.count(cell)) continue;
        bool adjacent = false;  // within two cells of a member: a missing patch may lie between
        for (int dp = -2; dp <= 2 && !adjacent; ++dp)
          for (int dq = -2; dq <= 2; ++dq)
            if (g.cell_quad.count({cell[0] + dp, cell[1] + dq})) {
              adjacent = true;
              break;
            }
        if (!adjacent) continue;
        // The quad's sides follow the local lattice axes and fit inside one pitch.
        const Point c = apply_homography(g.H, Point(cell[0], cell[1]));
        const Point P = apply_homography(g.H, Point(cell[0] + 0.5, cell[1])) - apply_homography(g.H, Point(cell[0] - 0.5, cell[1]));
        const Point Q = apply_homography(g.H, Point(cell[0], cell[1] + 0.5)) - apply_homography(g.H, Point(cell[0], cell[1] - 0.5));
        (void)c;
        const PatchQuad& q = quads[j];
        const bool a_on_P = parallel(q.side_a, P) >= parallel(q.side_a, Q);
        const Point& sp = a_on_P ? q.side_a : q.side_b;
        const Point& sq = a_on_P ? q.side_b : q.side_a;
        if (parallel(sp, P) < 0.94 || parallel(sq, Q) < 0.94) continue;
        const double fp = sp.norm() / P.norm(), fq = sq.norm() / Q.norm();
        if (fp < 0.3 || fp > 1.1 || fq < 0.3 || fq > 1.1 || std::max(fp, fq) > 1.5 * std::min(fp, fq)) continue;
        // ... and its size matches the members' (not two patches run together).
        const double expected = two_rows ? fill * cell_area(g.H, cell) : median_area;
        if (q.area > 1.7 * expected || q.area < 0.45 * expected) continue;
        auto it = offers.find(cell);
        if (it == offers.end() || res < it->second.first) offers[cell] = {res, j};
      }
      if (offers.empty()) {
        // Stalled: once more with the homography on two rows, which predicts the next cells of
        // a lattice in strong perspective (a lattice that reached 3 × 3 has it already). When
        // that adds no cell either, the lattice keeps the map it had.
        if (two_rows || !on_two_rows(g)) {
          if (two_rows && stalled_at == g.cell_quad.size()) g.H = stalled_H;
          break;
        }
        two_rows = true;
        stalled_at = g.cell_quad.size();
        stalled_H = g.H;
        refit(g, centre, true);
        continue;
      }
      for (const auto& kv : offers) {
        g.cell_quad[kv.first] = kv.second.second;
        members.insert(kv.second.second);
      }
      refit(g, centre, two_rows);
    }
    GridGroup group;
    if (!to_group(g, min_cells, [](int m) { return m; }, group)) continue;
    for (int m : group.quads) used[m] = 1;
    groups.push_back(std::move(group));
  }
  std::stable_sort(groups.begin(), groups.end(), [](const GridGroup& a, const GridGroup& b) { return a.cells.size() > b.cells.size(); });
  return groups;
}

namespace {

// A flat region's pixel count and moments.
struct RegionShape {
  long count = 0;
  bool border = false;                                 // touches the image border
  Point centre = Point::Zero();                        // mean of the pixel centres
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();    // their covariance, px²
};

std::vector<RegionShape> region_shapes(const RegionLabels& regions) {
  const int w = regions.width, h = regions.height;
  std::vector<RegionShape> out(size_t(std::max(0, regions.count)));
  std::vector<std::array<double, 5>> sums(out.size(), {0, 0, 0, 0, 0});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int l = regions.label[size_t(y) * w + x];
      if (l < 0) continue;
      RegionShape& s = out[size_t(l)];
      ++s.count;
      s.border = s.border || x <= 1 || y <= 1 || x >= w - 2 || y >= h - 2;
      const double px = x + 0.5, py = y + 0.5;
      auto& m = sums[size_t(l)];
      m[0] += px, m[1] += py, m[2] += px * px, m[3] += px * py, m[4] += py * py;
    }
  for (size_t l = 0; l < out.size(); ++l) {
    RegionShape& s = out[l];
    if (s.count == 0) continue;
    const auto& m = sums[l];
    const double n = double(s.count);
    s.centre = Point(m[0] / n, m[1] / n);
    s.spread << m[2] / n - s.centre.x() * s.centre.x(), m[3] / n - s.centre.x() * s.centre.y(),
        m[3] / n - s.centre.x() * s.centre.y(), m[4] / n - s.centre.y() * s.centre.y();
  }
  return out;
}

}  // namespace

std::vector<GridGroup> group_regions(const std::vector<PatchQuad>& quads, const RegionLabels& regions, int min_cells) {
  const std::vector<RegionShape> shape = region_shapes(regions);
  const int w = regions.width, h = regions.height;
  const long min_pixels = QuadOptions{}.min_pixels;
  auto label_at = [&](const Point& p) {
    if (!(p.x() >= 0 && p.y() >= 0 && p.x() < w && p.y() < h)) return -1;
    return regions.label[size_t(p.y()) * w + size_t(p.x())];
  };
  // The quad of each region (a quad's centre lies in its own region), else -1.
  std::vector<int> quad_of(shape.size(), -1);
  for (size_t i = 0; i < quads.size(); ++i) {
    const int l = label_at(quads[i].centre);
    if (l >= 0 && quad_of[size_t(l)] < 0) quad_of[size_t(l)] = static_cast<int>(i);
  }
  const auto centre = [&](int l) { return shape[size_t(l)].centre; };
  // Whether region l is the flat interior of one patch at lattice cell `cell` of the map H: its
  // centre within 0.3 cell of the cell's, its extent (a uniform square of side s has variance
  // s²/12 along any direction) within one pitch along each lattice axis, fewer pixels than the
  // cell's image — not two patches run together, not the background around the chart.
  auto one_patch = [&](int l, const Eigen::Matrix3d& H, const Eigen::Matrix3d& Hi, const std::array<int, 2>& cell) {
    const RegionShape& s = shape[size_t(l)];
    if (s.count < min_pixels || s.border) return false;
    const Point at = apply_homography(Hi, s.centre);
    if (std::abs(at.x() - cell[0]) > 0.3 || std::abs(at.y() - cell[1]) > 0.3) return false;
    const Point c(cell[0], cell[1]);
    const Point P = apply_homography(H, c + Point(0.5, 0)) - apply_homography(H, c - Point(0.5, 0));
    const Point Q = apply_homography(H, c + Point(0, 0.5)) - apply_homography(H, c - Point(0, 0.5));
    if (double(s.count) > cell_area(H, cell)) return false;
    const Point u = P.normalized(), v = Q.normalized();
    return 12 * u.dot(s.spread * u) <= P.squaredNorm() && 12 * v.dot(s.spread * v) <= Q.squaredNorm();
  };
  std::vector<char> used(shape.size(), 0);
  std::vector<GridGroup> groups;
  for (const PatchQuad& seed : quads) {
    const int own = label_at(seed.centre);
    if (own < 0 || used[size_t(own)]) continue;
    // The pitch along each of the quad's axes: the nearest region on either side along it whose
    // centre lies on the axis (as group_grids' neighbours: 0.9..2.6 sides away, 0.2 across).
    Eigen::Matrix2d B;
    B.col(0) = seed.side_a;
    B.col(1) = seed.side_b;
    if (std::abs(B.determinant()) < 1e-9) continue;
    const Eigen::Matrix2d Bi = B.inverse();
    Point step[2] = {Point::Zero(), Point::Zero()};
    double nearest[2] = {1e9, 1e9};
    for (int axis = 0; axis < 2; ++axis)
      for (int sign : {1, -1})
        for (double t = 0.8; t <= 2.6; t += 0.1) {
          const int m = label_at(seed.centre + sign * t * B.col(axis));
          if (m < 0 || m == own || shape[size_t(m)].count < min_pixels) continue;
          const Point d = shape[size_t(m)].centre - seed.centre;
          const Point ab = Bi * d;
          const double along = sign * ab[axis], across = ab[1 - axis];
          if (along < 0.9 || along > 2.6 || std::abs(across) > 0.2 * along + 0.15) continue;
          if (along < nearest[axis]) nearest[axis] = along, step[axis] = sign * d;
          break;
        }
    if (nearest[0] > 9 || nearest[1] > 9 || std::max(nearest[0], nearest[1]) > 1.3 * std::min(nearest[0], nearest[1]))
      continue;
    Growth g;
    g.cell_quad[{0, 0}] = own;
    std::set<int> members = {own};
    g.H << step[0].x(), step[1].x(), seed.centre.x(), step[0].y(), step[1].y(), seed.centre.y(), 0, 0, 1;
    for (int round = 0; round < 400; ++round) {
      const Eigen::Matrix3d Hi = g.H.inverse();
      std::map<std::array<int, 2>, int> offers;  // cell -> region
      std::set<int> offered;
      for (const auto& kv : g.cell_quad)
        for (int dp = -2; dp <= 2; ++dp)
          for (int dq = -2; dq <= 2; ++dq) {
            const std::array<int, 2> cell = {kv.first[0] + dp, kv.first[1] + dq};
            if (g.cell_quad.count(cell) || offers.count(cell)) continue;
            // The region at the cell's predicted centre, or a little off it (a flat interior
            // eaten into by noise).
            const Point c = apply_homography(g.H, Point(cell[0], cell[1]));
            const Point P = apply_homography(g.H, Point(cell[0] + 0.15, cell[1])) - c;
            const Point Q = apply_homography(g.H, Point(cell[0], cell[1] + 0.15)) - c;
            for (const Point& at : {c, Point(c + P), Point(c - P), Point(c + Q), Point(c - Q)}) {
              const int m = label_at(at);
              if (m < 0 || used[size_t(m)] || members.count(m) || offered.count(m) || !one_patch(m, g.H, Hi, cell))
                continue;
              offers[cell] = m;
              offered.insert(m);
              break;
            }
          }
      if (offers.empty()) break;
      for (const auto& kv : offers) g.cell_quad[kv.first] = kv.second, members.insert(kv.second);
      refit(g, centre);
    }
    GridGroup group;
    if (!to_group(g, min_cells, [&](int l) { return quad_of[size_t(l)]; }, group)) continue;
    for (const auto& kv : g.cell_quad) used[size_t(kv.second)] = 1;
    groups.push_back(std::move(group));
  }
  std::stable_sort(groups.begin(), groups.end(), [](const GridGroup& a, const GridGroup& b) { return a.cells.size() > b.cells.size(); });
  return groups;
}

}  // namespace tristim

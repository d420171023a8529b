// Chart detection, steps 5 and 7: placing the layout on a lattice (rotation, mirror, offset) by
// the residual of a quick 3×3 fit to the reference colours (detect.hpp), robust to glare and a
// cast shadow (docs/detection.md, "The colour fit under glare and shadow").
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
constexpr double kLn10 = 2.302585092994045684;
constexpr double kStep = 0.22314355131420976;  // ln 1.25
constexpr double kPi = 3.14159265358979323846;

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

// The patches left out of the fit: the unreliable ones, when they are at most a third of the
// pairs and 6 others remain (else none: more is no longer glare or a shadow's edge, and a fit
// on the rest could make a wrong placement fit — a lattice half on another grid).
std::vector<bool> usable_flags(const std::vector<bool>& unreliable, size_t n) {
  size_t bad = 0;
  for (bool u : unreliable) bad += u;
  if (unreliable.empty() || 3 * bad > n || n - bad < 6) return std::vector<bool>(n, false);
  return unreliable;
}

// The patches a highlight may reach: those flagged unreliable (clipped, or lit unevenly across
// their sample) and their 8 neighbours on the chart's grid (a spot's centre can light a patch
// evenly; its tail crosses the neighbours). Neighbours are told by `positions` (u, v in 0..1
// across the grid): within one grid step, the smallest non-zero difference of u (of v).
std::vector<char> glare_reach(const std::vector<Eigen::Vector2d>& positions, const std::vector<bool>& unreliable,
                              size_t n) {
  std::vector<char> out(n, 0);
  if (unreliable.empty()) return out;
  for (size_t k = 0; k < n; ++k) out[k] = unreliable[k];
  if (positions.size() != n) return out;
  double du = 1e300, dv = 1e300;
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b) {
      const double x = std::abs(positions[a].x() - positions[b].x()), y = std::abs(positions[a].y() - positions[b].y());
      if (x > 1e-9) du = std::min(du, x);
      if (y > 1e-9) dv = std::min(dv, y);
    }
  for (size_t a = 0; a < n; ++a)
    if (unreliable[a])
      for (size_t b = 0; b < n; ++b)
        out[b] = out[b] || (std::abs(positions[a].x() - positions[b].x()) < 1.5 * du &&
                            std::abs(positions[a].y() - positions[b].y()) < 1.5 * dv);
  return out;
}

// The terms of the smooth light at a chart position (u, v in 0..1): 1, u, v, u², v², uv.
std::array<double, 6> light_terms(const Eigen::Vector2d& at) {
  const double u = at.x() - 0.5, v = at.y() - 0.5;
  return {1, u, v, u * u, v * v, u * v};
}

// A cast shadow's step in the light, fitted with the smooth light: log L = β·φ(u, v) + δ·s,
// s = 1 on one side of a straight line across the chart and 0 on the other, by least squares on
// `rho` (each patch's log light, where `ok`). Every line in 12 directions that splits the ok
// patches with 4 or more on each side is tried; for a split s the joint fit's error is that of
// the smooth fit less (sᵀr)² / (sᵀPs), r = Pρ, P the projection away from the smooth terms
// (O(terms²) per split from running sums). The best split is kept when it halves the smooth
// fit's error and |δ| > ln 1.25 (a step of 20 %): then `step` holds δ (within ln 10) on its side
// and 0 elsewhere, for every patch, `beta` the smooth terms, and the result is true.
// The patches in order along each of the 12 directions of shadow_step (their projection, index).
using LineOrders = std::array<std::vector<std::pair<double, size_t>>, 12>;
LineOrders line_orders(const std::vector<Eigen::Vector2d>& positions) {
  LineOrders out;
  for (int d = 0; d < 12; ++d) {
    const double th = kPi * d / 12, cs = detmath::cos(th), sn = detmath::sin(th);
    for (size_t k = 0; k < positions.size(); ++k)
      out[size_t(d)].emplace_back((positions[k].x() - 0.5) * cs + (positions[k].y() - 0.5) * sn, k);
    std::sort(out[size_t(d)].begin(), out[size_t(d)].end());
  }
  return out;
}

bool shadow_step(const std::vector<Eigen::Vector2d>& positions, const LineOrders& orders, const std::vector<double>& rho,
                 const std::vector<char>& ok, int terms, std::vector<double>& step, Eigen::VectorXd& beta) {
  const size_t n = rho.size(), side = 4;
  std::fill(step.begin(), step.end(), 0.0);
  // With the step, the smooth light is linear (1, u, v): a quadratic could bend into a step where
  // a row of patches at the shadow's edge is left out, and would then be clamped. Fixed-size
  // algebra: this runs for every placement of a Digital SG.
  std::vector<size_t> idx;
  std::vector<Eigen::Vector3d> phi;
  for (size_t k = 0; k < n; ++k)
    if (ok[k]) {
      idx.push_back(k);
      const auto t = light_terms(positions[k]);
      phi.emplace_back(t[0], t[1], t[2]);
    }
  const size_t m = idx.size();
  if (m < 2 * side + 3) return false;
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Phi_y = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < m; ++i) {
    G += phi[i] * phi[i].transpose();
    Phi_y += phi[i] * rho[idx[i]];
  }
  G += 1e-12 * G.trace() * Eigen::Matrix3d::Identity();
  const Eigen::LDLT<Eigen::Matrix3d> solver(G);
  const Eigen::Matrix3d Gi = solver.solve(Eigen::Matrix3d::Identity());
  const Eigen::Vector3d b0 = solver.solve(Phi_y);
  std::vector<double> r(m);  // r = Pρ
  double sse0 = 0;
  for (size_t i = 0; i < m; ++i) {
    r[i] = rho[idx[i]] - phi[i].dot(b0);
    sse0 += r[i] * r[i];
  }
  double best = 0.5 * sse0, best_delta = 0, best_cs = 0, best_sn = 0, best_cut = 0;
  bool found = false;
  std::vector<size_t> row_of(n, 0);  // patch -> its row among the ok ones
  for (size_t i = 0; i < m; ++i) row_of[idx[i]] = i;
  std::vector<std::pair<double, size_t>> order;
  for (int d = 0; d < 12; ++d) {
    const double th = kPi * d / 12, cs = detmath::cos(th), sn = detmath::sin(th);
    order.clear();
    for (const auto& e : orders[size_t(d)])
      if (ok[e.second]) order.emplace_back(e.first, row_of[e.second]);
    double sr = 0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();  // Φᵀs
    for (size_t i = 0; i + 1 < m; ++i) {
      const size_t row = order[i].second;
      sr += r[row];
      g += phi[row];
      const size_t nl = i + 1;
      if (nl < side || m - nl < side || !(order[i + 1].first - order[i].first > 1e-9)) continue;
      const double q = double(nl) - g.dot(Gi * g);  // sᵀPs
      if (!(q > 1e-6 * double(nl))) continue;
      const double sse = sse0 - sr * sr / q, delta = sr / q;
      if (sse < best && std::abs(delta) > kStep) {
        best = sse, best_delta = delta, best_cs = cs, best_sn = sn, found = true;
        best_cut = (order[i].first + order[i + 1].first) / 2;
      }
    }
  }
  if (!found) return false;
  best_delta = std::min(kLn10, std::max(-kLn10, best_delta));
  for (size_t k = 0; k < n; ++k)
    step[k] = (positions[k].x() - 0.5) * best_cs + (positions[k].y() - 0.5) * best_sn < best_cut ? best_delta : 0.0;
  Eigen::Vector3d Phi_rest = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < m; ++i) Phi_rest += phi[i] * (rho[idx[i]] - step[idx[i]]);
  beta = Eigen::VectorXd::Zero(terms);
  beta.head<3>() = solver.solve(Phi_rest);
  return true;
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

// A lattice cell's sample in place_layout: its mean, whether it is clipped or not uniform, and
// whether a larger square about it is (a highlight's tail that has not reached the centre).
struct CellSample {
  bool inside = false;
  Vec3 mean = Vec3::Zero();
  bool unreliable = false, highlight = false;
};

// Mean RGB of the pixels [x0, x1] × [y0, y1] (inside the image).
Vec3 box_mean(const RawImage& img, int x0, int y0, int x1, int y1) {
  Vec3 mean = Vec3::Zero();
  int n = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x, ++n)
      for (int k = 0; k < 3; ++k) mean[k] += img.at(x, y, k);
  return mean / double(std::max(1, n));
}

// Whether the pixels [x0, x1] × [y0, y1] are unfit for the colour fit: a clipped pixel, or in a
// channel the means of the four quadrants differ by more than `threshold` of the mean and by 4
// standard errors (sample_chart's "nonuniform" test: a highlight or a shadow's edge across it).
bool unevenly_lit(const RawImage& img, int x0, int y0, int x1, int y1, double threshold) {
  Vec3 quadrant[4] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Vec3 sum = Vec3::Zero(), sq = Vec3::Zero();
  int count[4] = {0, 0, 0, 0}, n = 0;
  const bool sat = img.saturated.size() == size_t(img.width) * img.height;
  const int xm = (x0 + x1 + 1) / 2, ym = (y0 + y1 + 1) / 2;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x, ++n) {
      if (sat && img.saturated[size_t(y) * img.width + x]) return true;
      const int q = (x >= xm) + 2 * (y >= ym);
      ++count[q];
      for (int k = 0; k < 3; ++k) {
        const double v = img.at(x, y, k);
        sum[k] += v;
        quadrant[q][k] += v;
        sq[k] += v * v;
      }
    }
  if (n < 2 || !count[0] || !count[1] || !count[2] || !count[3]) return false;
  for (int k = 0; k < 3; ++k) {
    const double mean = sum[k] / n;
    double qmin = 1e300, qmax = -1e300;
    for (int q = 0; q < 4; ++q) {
      qmin = std::min(qmin, quadrant[q][k] / count[q]);
      qmax = std::max(qmax, quadrant[q][k] / count[q]);
    }
    const double standard_error = std::sqrt(std::max(0.0, (sq[k] - n * mean * mean) / (n - 1)) / (n / 4.0));
    if (qmax - qmin > threshold * mean && qmax - qmin > 4.0 * standard_error) return true;
  }
  return false;
}

}  // namespace

namespace {

// One run of the fit of reference_fit_residuals: the residuals with the glare (`e`) and without
// it (`glare_free`; the same when no glare is modelled), and the score on the latter.
struct FitRun {
  std::vector<double> e, glare_free;
  double score = 0;
};

// The fit, without glare (`highlights` empty) or with it on the patches glare_reach finds from
// `highlights` (flags of patches seen lit unevenly, maybe over a larger area than `unreliable`'s).
FitRun fit_run(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const std::vector<Eigen::Vector2d>& positions,
               const std::vector<bool>& unreliable, const std::vector<bool>& highlights) {
  const size_t n = rgb.size();
  FitRun out;
  std::vector<double>* glare_free = &out.glare_free;
  const std::vector<bool> left_out = usable_flags(unreliable, n);
  // Relative errors: weight 1/|ref|² (the camera scale is unknown, the reference sets the level).
  double brightest = 0;
  for (const auto& r : ref) brightest = std::max(brightest, r.squaredNorm());
  std::vector<double> w0(n), w(n);
  for (size_t k = 0; k < n; ++k)
    w0[k] = w[k] = left_out[k] ? 0.0 : 1.0 / (ref[k].squaredNorm() + 4e-4 * brightest + 1e-30);
  // Light across the chart: log L = β · (1, u, v[, u², v², uv]) (linear from 12 patches,
  // quadratic from 24), each factor within 0.5..2 of 1; and from 12 patches a step δ beyond a
  // straight line (a cast shadow).
  const int terms = positions.empty() || n < 12 ? 0 : n < 24 ? 3 : 6;
  std::vector<double> light(n, 1.0), step(n, 0.0), rho(n, 0.0);
  std::vector<char> lit_ok(n, 0);
  std::vector<Vec3> lit = ref;
  std::vector<double> e, sorted;
  // Glare: a highlight adds the illuminant's colour to a patch, rgb = M · (L·ref + g·white) with
  // g >= 0 (the reference's brightest colour stands for the white: its direction is all that
  // counts), on the patches a highlight may reach (glare_reach). They are left out of the first
  // fit (when 6 others remain); then g is fitted per patch with M, and they count again.
  const std::vector<char> reach = glare_reach(positions, highlights, n);
  size_t reached = 0;
  for (char r : reach) reached += r;
  Vec3 white = ref.front();
  for (const auto& r : ref)
    if (r.squaredNorm() > white.squaredNorm()) white = r;
  std::vector<double> glare(n, 0.0);
  size_t flagged = 0;
  for (bool u : highlights) flagged += u;
  for (size_t k = 0; k < n && reached; ++k)
    if (n - reached >= 6 ? reach[k] : n - flagged >= 6 && highlights[k]) w[k] = 0;
  // The light across the chart is then fitted on the patches no highlight reaches, when 8 remain.
  // (else on those not flagged).
  const bool light_from_unreached = reached && n - reached >= 8;
  auto unreliable_at = [&](size_t k) { return reached && highlights[k]; };
  const int iterations = reached ? (terms ? 7 : 5) : terms ? 5 : 2;
  const LineOrders orders = terms ? line_orders(positions) : LineOrders{};
  for (int it = 0; it < iterations; ++it) {
    for (size_t k = 0; k < n; ++k) lit[k] = light[k] * ref[k] + glare[k] * white;
    Mat3 M = fit_matrix(rgb, lit, w);
    e = relative_residuals(rgb, lit, M);
    if (reached && it == 0) {
      // A robust start: a highlight's centre can be lit evenly (not flagged) and still be in the
      // first fit; the worst quarter of the patches it used are dropped and M refitted.
      sorted.clear();
      for (size_t k = 0; k < n; ++k)
        if (w[k] > 0) sorted.push_back(e[k]);
      if (sorted.size() >= 8) {
        const auto q3 = sorted.begin() + static_cast<std::ptrdiff_t>(std::floor(0.75 * (sorted.size() - 1)));
        std::nth_element(sorted.begin(), q3, sorted.end());
        std::vector<double> trimmed = w;
        for (size_t k = 0; k < n; ++k)
          if (e[k] > *q3) trimmed[k] = 0;
        M = fit_matrix(rgb, lit, trimmed);
        e = relative_residuals(rgb, lit, M);
      }
    }
    if (it == iterations - 1) {
      // What is returned: each patch against M·L·ref, its glare included (a highlight shows).
      if (glare_free) *glare_free = e;
      if (reached) {
        for (size_t k = 0; k < n; ++k) lit[k] = light[k] * ref[k];
        e = relative_residuals(rgb, lit, M);
      }
      break;  // the weights and light below would only serve a next fit
    }
    // Each reachable patch's glare: the non-negative amount of M·white that best closes its gap.
    const Vec3 Mw = M * white;
    if (reached) {
      for (size_t k = 0; k < n; ++k) {
        if (reach[k]) glare[k] = std::max(0.0, (rgb[k] - M * (light[k] * ref[k])).dot(Mw) / (Mw.squaredNorm() + 1e-300));
        lit[k] = light[k] * ref[k] + glare[k] * white;
      }
      e = relative_residuals(rgb, lit, M);  // the refit's weights below: with the glare
    }
    // Refit without the worst 25 % of the patches kept (glare, a shadow, a missing patch).
    sorted.clear();
    for (size_t k = 0; k < n; ++k)
      if (!left_out[k]) sorted.push_back(e[k]);
    const auto q3 = sorted.begin() + static_cast<std::ptrdiff_t>(std::floor(0.75 * (sorted.size() - 1)));
    std::nth_element(sorted.begin(), q3, sorted.end());
    const double cut = *q3;
    for (size_t k = 0; k < n; ++k) w[k] = e[k] > cut ? 0 : w0[k];
    // Under glare the light waits two rounds: M and the glare first (from the patches the
    // refit keeps), else the light bends to explain the highlights.
    if (!terms || (reached && it < 2)) continue;
    // Each patch's light relative to M: ρ = log(rgb·p / |p|²), p = M · ref (bright enough ones).
    for (size_t k = 0; k < n; ++k) {
      const Vec3 p = M * ref[k];
      const double r = (rgb[k] - glare[k] * Mw).dot(p) / (p.squaredNorm() + 1e-300);
      lit_ok[k] = !left_out[k] && !(light_from_unreached ? reach[k] : unreliable_at(k)) && r > 0 && p.squaredNorm() >= 4e-3 * brightest * M.squaredNorm() / 3;
      rho[k] = lit_ok[k] ? detmath::log(r) : 0.0;
    }
    // A shadow's step with the smooth light, on every reliable patch (the refit's weights may
    // have dropped the whole lit or shadowed side); else the smooth light alone on the patches
    // the refit keeps.
    Eigen::VectorXd beta;
    if (!shadow_step(positions, orders, rho, lit_ok, terms, step, beta)) {
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), terms);
      Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
      for (size_t k = 0; k < n; ++k) {
        if (!lit_ok[k] || !(w[k] > 0)) continue;
        const auto phi = light_terms(positions[k]);
        for (int j = 0; j < terms; ++j) A(static_cast<Eigen::Index>(k), j) = phi[size_t(j)];
        b(static_cast<Eigen::Index>(k)) = rho[k];
      }
      beta = A.colPivHouseholderQr().solve(b);
    }
    for (size_t k = 0; k < n; ++k) {
      const auto phi = light_terms(positions[k]);
      double l = 0;
      for (int j = 1; j < terms; ++j) l += beta(j) * phi[size_t(j)];  // the constant stays in M
      light[k] = detmath::exp(std::min(kLn2, std::max(-kLn2, l)) + step[k]);
    }
  }
  out.e = std::move(e);
  // The score: the patches left out of the fit are left out of it (a third of them at most).
  std::vector<double> kept;
  for (size_t k = 0; k < n; ++k)
    if (!left_out[k]) kept.push_back(out.glare_free[k]);
  out.score = trimmed_mean(kept);
  return out;
}

// Glare is modelled on charts of at most this many patches. On a Digital SG (140) a spot reaches a
// few % of the patches, which the robust fit leaves out or trims; its g per patch, free on the
// neighbours of every cell flagged along a shadow's edge, let wrong placements of a small lattice
// fit as well as the right one (a tilted SG under a shadow: 0.056 against 0.080).
constexpr size_t kGlareMostPatches = 48;

// The fit without glare, and, when a patch is flagged in `highlights`, the fit with it, kept when
// it halves the score (its g per patch can explain a little of any misfit: a wrong placement
// gains too, though less). A cast shadow's edge is flagged as a highlight is (the sample is uneven);
// glare is additive, of the illuminant's colour, where a shadow takes light in proportion — each
// model explains its own and the score tells which one the patches show.
FitRun fit_best(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const std::vector<Eigen::Vector2d>& positions,
                const std::vector<bool>& unreliable, const std::vector<bool>& highlights) {
  const size_t n = rgb.size();
  if (ref.size() != n || n < 4 || (!positions.empty() && positions.size() != n) ||
      (!unreliable.empty() && unreliable.size() != n) || (!highlights.empty() && highlights.size() != n))
    throw Error(ErrorCode::InvalidArgument, "the 3x3 reference fit needs 4 or more camera/reference pairs");
  FitRun plain = fit_run(rgb, ref, positions, unreliable, {});
  if (n > kGlareMostPatches || std::none_of(highlights.begin(), highlights.end(), [](bool b) { return b; })) return plain;
  FitRun glare = fit_run(rgb, ref, positions, unreliable, highlights);
  return glare.score < 0.5 * plain.score ? glare : plain;
}

// The score of one placement without the glare model and with it (the same when it does not
// apply: no patch flagged in `highlights`, or more than kGlareMostPatches).
FitScores fit_scores(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref, const std::vector<Eigen::Vector2d>& positions,
                     const std::vector<bool>& unreliable, const std::vector<bool>& highlights) {
  const double plain = fit_run(rgb, ref, positions, unreliable, {}).score;
  if (rgb.size() > kGlareMostPatches || std::none_of(highlights.begin(), highlights.end(), [](bool b) { return b; }))
    return {plain, plain};
  return {plain, std::min(plain, fit_run(rgb, ref, positions, unreliable, highlights).score)};
}

}  // namespace

std::vector<double> reference_fit_residuals(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref,
                                            const std::vector<Eigen::Vector2d>& positions,
                                            const std::vector<bool>& unreliable, std::vector<double>* glare_free) {
  FitRun run = fit_best(rgb, ref, positions, unreliable, unreliable);
  if (glare_free) *glare_free = std::move(run.glare_free);
  return run.e;
}

double reference_fit_score(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref,
                           const std::vector<Eigen::Vector2d>& positions, const std::vector<bool>& unreliable) {
  return fit_best(rgb, ref, positions, unreliable, unreliable).score;
}

FitScores reference_fit_scores(const std::vector<Vec3>& rgb, const std::vector<Vec3>& ref,
                               const std::vector<Eigen::Vector2d>& positions, const std::vector<bool>& unreliable) {
  if (ref.size() != rgb.size() || rgb.size() < 4 || (!positions.empty() && positions.size() != rgb.size()) ||
      (!unreliable.empty() && unreliable.size() != rgb.size()))
    throw Error(ErrorCode::InvalidArgument, "the 3x3 reference fit needs 4 or more camera/reference pairs");
  return fit_scores(rgb, ref, positions, unreliable, unreliable);
}

bool rank_with_glare(const std::vector<FitScores>& rivals, int chosen) {
  // How far the best (or the chosen) fit stands from the best other one, under one model.
  const auto margin = [&](double FitScores::*model) {
    size_t best = chosen >= 0 ? static_cast<size_t>(chosen) : 0;
    if (chosen < 0)
      for (size_t i = 1; i < rivals.size(); ++i) best = rivals[i].*model < rivals[best].*model ? i : best;
    double other = 1e9;
    for (size_t i = 0; i < rivals.size(); ++i)
      if (i != best) other = std::min(other, rivals[i].*model);
    return std::make_pair(rivals[best].*model, other / std::max(rivals[best].*model, 1e-6));
  };
  if (rivals.empty()) return false;
  const auto [plain, plain_margin] = margin(&FitScores::plain);
  const auto [glare, glare_margin] = margin(&FitScores::glare);
  return glare < 0.5 * plain && (rivals.size() < 2 || glare_margin > plain_margin);
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
  std::vector<CellSample> cache(size_t(cache_w) * cache_h);
  std::vector<char> cached(cache.size(), 0);
  const double threshold = reference_fit_nonuniform;
  auto sample = [&](const std::array<int, 2>& cell) -> const CellSample& {
    const size_t slot = size_t(cell[1] - cache_q0) * cache_w + size_t(cell[0] - cache_p0);
    if (cached[slot]) return cache[slot];
    const Point c = apply_homography(H, Point(cell[0], cell[1]));
    const double pitch = std::min((apply_homography(H, Point(cell[0] + 1, cell[1])) - c).norm(),
                                  (apply_homography(H, Point(cell[0], cell[1] + 1)) - c).norm());
    const double r = std::max(0.5, 0.2 * pitch);
    const int x0 = static_cast<int>(std::floor(c.x() - r)), x1 = static_cast<int>(std::ceil(c.x() + r));
    const int y0 = static_cast<int>(std::floor(c.y() - r)), y1 = static_cast<int>(std::ceil(c.y() + r));
    CellSample s;
    if (std::isfinite(c.x()) && std::isfinite(c.y()) && x0 >= 0 && y0 >= 0 && x1 < img.width && y1 < img.height) {
      s.inside = true;
      s.mean = box_mean(img, x0, y0, x1, y1);
      s.unreliable = unevenly_lit(img, x0, y0, x1, y1, threshold);
      // For the glare model: the test at ±35 % of the pitch (within the patch, clear of its edges).
      const double ro = std::max(r, 0.35 * pitch);
      const int u0 = static_cast<int>(std::floor(c.x() - ro)), u1 = static_cast<int>(std::ceil(c.x() + ro));
      const int w0 = static_cast<int>(std::floor(c.y() - ro)), w1 = static_cast<int>(std::ceil(c.y() + ro));
      s.highlight = u0 < 0 || w0 < 0 || u1 >= img.width || w1 >= img.height ? s.unreliable
                                                                              : unevenly_lit(img, u0, w0, u1, w1, threshold);
    }
    cached[slot] = 1;
    return cache[slot] = s;
  };
  // Chart unit square -> layout (column, row) coordinates of the cell centres (affine).
  const PatchCell& first = layout.patches.front();
  const double pw = (first.u1 - first.u0) * (1 + layout.gap), ph = (first.v1 - first.v0) * (1 + layout.gap);
  const double uc0 = (first.u0 + first.u1) / 2, vc0 = (first.v0 + first.v1) / 2;
  std::vector<Placement> out;
  std::vector<FitScores> scores;  // each placement's, without and with the glare model
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
        std::vector<bool> unreliable, highlights;
        int outside = 0;
        for (int k = 0; k < N; ++k) {
          const auto& cell = layout.patches[k];
          const auto pq = dihedral(t, cell.column, cell.row);
          const auto& s = sample({pq[0] + op, pq[1] + oq});
          if (!s.inside) {
            ++outside;
            continue;
          }
          rgb.push_back(s.mean);
          unreliable.push_back(s.unreliable);
          highlights.push_back(s.highlight);
          where.emplace_back(C > 1 ? cell.column / (C - 1.0) : 0.5, R > 1 ? cell.row / (R - 1.0) : 0.5);
          if (!reference.empty()) ref.push_back(reference[k]);
        }
        pl.inside = outside == 0;
        if (rgb.size() < std::max<size_t>(6, N / 2)) continue;
        scores.push_back(reference.empty() ? FitScores{} : fit_scores(rgb, ref, where, unreliable, highlights));
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
  // One model ranks all the placements of the lattice: per placement the glare model only lowers a
  // score, a wrong placement's too, so chosen per placement it took a clean chart's margin away.
  const bool glare = rank_with_glare(scores);
  for (size_t i = 0; i < out.size(); ++i) out[i].residual = glare ? scores[i].glare : scores[i].plain;
  std::stable_sort(out.begin(), out.end(), [](const Placement& a, const Placement& b) { return a.residual < b.residual; });
  return out;
}

}  // namespace tristim

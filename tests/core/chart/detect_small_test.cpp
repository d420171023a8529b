// Small Digital SG charts (issue 48): ~14 px patches without a gap, in the detector's finer pass
// (the image enlarged twice). Noise and blur leave each patch a ragged flat interior that
// patch_quads refuses, so group_grids finds no lattice of 4; group_regions grows one from single
// quads into the flat regions that are not quads.
#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "chart_scene.hpp"
#include "test_support.hpp"
#include "tristim/chart/detect.hpp"

using namespace tristim;

namespace {

// A label image with one region per cell of an 11 × 9 lattice (pitch ~20 px, rotated 30°, in mild
// perspective): ragged blobs of ~0.3 pitch around each cell centre, the cell (0, 0) a clean
// parallelogram (the one quad). `scatter`: the same blobs at random places instead (no lattice).
struct Planted {
  RegionLabels regions;
  std::vector<PatchQuad> quads;
  Eigen::Matrix3d H;
};

Planted planted_lattice(bool scatter) {
  Planted out;
  const double a = 30 * 3.14159265358979323846 / 180;
  out.H << 20 * std::cos(a), -18 * std::sin(a) + 1, 200, 20 * std::sin(a), 18 * std::cos(a), 150, 4e-4, -3e-4, 1;
  RegionLabels& r = out.regions;
  r.width = 400, r.height = 300;
  r.label.assign(size_t(r.width) * r.height, -1);
  std::uint64_t state = 12345;
  auto uniform = [&] {  // portable (native and wasm): a 64-bit LCG's top bits
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  };
  for (int p = -5; p <= 5; ++p)
    for (int q = -4; q <= 4; ++q) {
      Eigen::Vector2d c = apply_homography(out.H, Eigen::Vector2d(p, q));
      if (scatter) c = Eigen::Vector2d(30 + 340 * uniform(), 30 + 240 * uniform());
      const double phase = 6.283 * uniform(), radius = 5.5;
      const int label = r.count++;
      const Eigen::Vector2d P = apply_homography(out.H, Eigen::Vector2d(p + 0.25, q)) - apply_homography(out.H, Eigen::Vector2d(p - 0.25, q));
      const Eigen::Vector2d Q = apply_homography(out.H, Eigen::Vector2d(p, q + 0.25)) - apply_homography(out.H, Eigen::Vector2d(p, q - 0.25));
      Eigen::Matrix2d B;
      B << P, Q;
      const Eigen::Matrix2d Bi = B.inverse();
      for (int y = int(c.y()) - 12; y <= int(c.y()) + 12; ++y)
        for (int x = int(c.x()) - 12; x <= int(c.x()) + 12; ++x) {
          if (x < 0 || y < 0 || x >= r.width || y >= r.height) continue;
          const Eigen::Vector2d d = Eigen::Vector2d(x + 0.5, y + 0.5) - c;
          const bool clean = p == 0 && q == 0 && !scatter;
          const Eigen::Vector2d ab = Bi * d;
          const bool inside = clean ? std::abs(ab.x()) <= 1 && std::abs(ab.y()) <= 1
                                    : d.norm() < radius * (1 + 0.3 * std::sin(3 * std::atan2(d.y(), d.x()) + phase));
          if (inside) r.label[size_t(y) * r.width + x] = label;
        }
      if (p == 0 && q == 0 && !scatter) {
        PatchQuad quad;
        quad.centre = c;
        quad.side_a = P, quad.side_b = Q;
        quad.corners = {c - P / 2 - Q / 2, c + P / 2 - Q / 2, c + P / 2 + Q / 2, c - P / 2 + Q / 2};
        quad.area = std::abs(P.x() * Q.y() - P.y() * Q.x());
        out.quads.push_back(quad);
      }
    }
  if (scatter) {  // a quad among the scattered blobs, as in the lattice
    PatchQuad quad;
    quad.centre = Eigen::Vector2d(200, 150);
    quad.side_a = Eigen::Vector2d(10, 0), quad.side_b = Eigen::Vector2d(0, 9);
    quad.area = 90;
    out.quads.push_back(quad);
  }
  return out;
}

}  // namespace

TEST_CASE("group_regions: a lattice of ragged flat regions grows from one quad to all 99 cells",
          "[detect][small]") {
  const Planted t = planted_lattice(false);
  // group_grids has one quad: no lattice.
  CHECK(group_grids(t.quads, 4).empty());
  const std::vector<GridGroup> groups = group_regions(t.quads, t.regions, 4);
  REQUIRE(groups.size() == 1);
  const GridGroup& g = groups.front();
  CHECK(g.cells.size() == 99);
  CHECK(g.p_max - g.p_min == 10);
  CHECK(g.q_max - g.q_min == 8);
  // The seed quad's cell is (0, 0) and its side_a the first axis: the fitted map is the planted one
  // (each cell centre within a twentieth of the ~20 px pitch); only the seed is a quad.
  double worst = 0;
  int quads = 0;
  for (size_t i = 0; i < g.cells.size(); ++i) {
    const Eigen::Vector2d l(g.cells[i][0], g.cells[i][1]);
    worst = std::max(worst, (apply_homography(g.lattice_to_image, l) - apply_homography(t.H, l)).norm());
    quads += g.quads[i] >= 0;
    if (g.quads[i] >= 0) CHECK((g.cells[i] == std::array<int, 2>{0, 0}));
  }
  INFO("worst cell centre " << worst << " px");
  CHECK(worst < 1.0);
  CHECK(quads == 1);
}

TEST_CASE("group_regions: the same blobs scattered form no lattice", "[detect][small]") {
  const Planted t = planted_lattice(true);
  const std::vector<GridGroup> groups = group_regions(t.quads, t.regions, 4);
  INFO(groups.size() << " lattices, the largest of " << (groups.empty() ? 0 : groups[0].cells.size()) << " cells");
  CHECK(groups.empty());
}

TEST_CASE("a Digital SG of 3.2 % of the frame tilted 37°: found in the finer pass within 0.5 px", "[detect][small]") {
  // Scene 13 of the failure kind "sg" (seed 1), blur 1.3 px instead of 1.64 and its own noise
  // seed: before group_regions it was missed ("the largest flat regions form no grid": 19
  // patch-like regions at full resolution; enlarged, no lattice either).
  DetectOptions o;
  o.charts = {"sg140"};
  SceneSpec s;
  s.chart = "sg140";
  s.width = 1200, s.height = 800;
  s.camera = "Canon_EOS_5DS";
  s.illuminant = "D65";
  s.area_fraction = 0.032343901685198934;
  s.tilt_deg = 36.854101457764699, s.tilt_axis_deg = 15.437757091788793, s.rotation_deg = 322.22803698273771;
  s.focal = 2.7068007189873704, s.cx = 0.48060155039335339, s.cy = 0.5882892006607281;
  s.gap = 0.2274;
  s.exposure = 0.50438407728758949, s.shot_gain = 5.1495551776624522, s.read_noise = 7.9984514225535159;
  s.blur_sigma = 1.3, s.vignetting = 0.38652828361198227, s.gradient = 0.26934476476011443;
  s.seed = 12;
  const ChartScene scene = render_chart_scene(s);
  const std::vector<ChartCandidate> found = detect_charts(scene.image, o);
  REQUIRE(!found.empty());
  const DetectionScore score = score_detection(scene, &found[0].corners, found[0].confidence);
  INFO("corner error " << score.corner_error << " px, worst " << max_corner_error(found[0].corners, scene.corners)
                       << ", confidence " << found[0].confidence);
  CHECK(score.oriented);
  CHECK(max_corner_error(found[0].corners, scene.corners) < 0.5);
  CHECK(found[0].confidence > 0.9);
  CHECK(found[0].missing.empty());
  CHECK(found.size() == 1);
  // Without the finer pass the chart is not found at all.
  o.finer_pass = false;
  CHECK(test::code_of([&] { detect_charts(scene.image, o); }) == ErrorCode::ChartNotFound);
}

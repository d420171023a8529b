// Lattice growth under strong perspective (issue 48): a ColorChecker Classic tilted 48° out of
// plane, seen from 1.3 chart heights, whose patches shrink by a third from one column to the next.
// An affine lattice map cannot follow that: grouping stopped at two rows (two lattices of 2 × 3
// here, and a candidate placed a row off the chart). Refitted as a homography on those two rows
// once growth stalls (group_grids), the lattice predicts the next cells and grows to the chart.
#include <algorithm>

#include <Eigen/LU>

#include "chart_scene.hpp"
#include "test_support.hpp"
#include "tristim/chart/detect.hpp"

using namespace tristim;

namespace {

SceneSpec strong_perspective() {
  SceneSpec s = plain_scene_spec("cc24", 311, 108);
  s.width = 1200, s.height = 800;
  s.tilt_deg = 48, s.tilt_axis_deg = 94, s.focal = 1.3, s.area_fraction = 0.08;
  return s;
}

}  // namespace

TEST_CASE("a Classic tilted 48°: the lattice grows past two rows and the chart is found within 0.5 px",
          "[detect][perspective]") {
  const ChartScene scene = render_chart_scene(strong_perspective());
  // Step 4 alone: one lattice over most of the chart's 24 patches, spanning more than two rows and
  // columns (before: the largest held 6 cells on two rows).
  const RegionLabels regions = flat_regions(scene.image);
  const std::vector<PatchQuad> quads = patch_quads(scene.image, regions);
  const std::vector<GridGroup> groups = group_grids(quads, 4);
  REQUIRE(!groups.empty());
  const GridGroup& g = groups.front();
  INFO(quads.size() << " quads; largest lattice " << g.cells.size() << " cells, p " << g.p_min << ".." << g.p_max
                    << ", q " << g.q_min << ".." << g.q_max);
  CHECK(g.cells.size() >= 18);
  CHECK(g.p_max - g.p_min >= 2);
  CHECK(g.q_max - g.q_min >= 2);
  // Every member sits on its lattice cell under the fitted homography (a tenth of a cell).
  const Eigen::Matrix3d Hi = g.lattice_to_image.inverse();
  double worst = 0;
  for (size_t i = 0; i < g.cells.size(); ++i) {
    const Eigen::Vector2d l = apply_homography(Hi, quads[size_t(g.quads[i])].centre);
    worst = std::max(worst, (l - Eigen::Vector2d(g.cells[i][0], g.cells[i][1])).norm());
  }
  CHECK(worst < 0.1);
  // The whole pipeline: the chart at the right place, A1 first, corners within 0.5 px.
  DetectOptions o;
  o.charts = {"cc24"};
  const std::vector<ChartCandidate> found = detect_charts(scene.image, o);
  REQUIRE(!found.empty());
  const DetectionScore s = score_detection(scene, &found[0].corners, found[0].confidence);
  INFO("corner error " << s.corner_error << " px, confidence " << found[0].confidence);
  CHECK(s.oriented);
  CHECK(max_corner_error(found[0].corners, scene.corners) < 0.5);
  CHECK(found[0].confidence > 0.9);
}

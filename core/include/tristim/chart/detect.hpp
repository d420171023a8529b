// tristim — automatic chart detection in a linear image (issue 12).
//
// Finds ColorChecker Classic 24 / Passport (classic side), ColorChecker Digital SG 140 and custom
// grid charts in a decoded linear image (RawImage: black-subtracted camera RGB, no white balance)
// and returns the four corners in the convention of chart/layout.hpp: the outer corners of the
// patch grid, clockwise from patch A1's outer corner, in the image's pixel coordinates (half
// resolution for a Bayer RAW: what `tristim sample --corners` takes).
//
// The pipeline, one function per step (each testable on its own):
//   1. working_image      box-downsamples the image so its longer side is <= DetectOptions::
//                         working_side, or <= 1000 px (a coarse pass) when that finds nothing;
//   2. flat_regions       labels the connected regions where the log image is flat (patch interiors),
//                         the threshold following a noise level estimated per brightness band;
//   3. patch_quads        keeps the regions shaped like a filled convex quadrilateral (a patch);
//   4. group_grids        grows lattices of equal-pitch quads (neighbour to neighbour, a DLT
//                         homography lattice -> image refitted as the lattice grows); for small
//                         patches also group_regions (from single quads into flat regions);
//   5. place_layout       tries every placement of the layout on a lattice: the 4 rotations, the
//                         mirror, and every offset, scoring each by the residual of a quick 3×3
//                         fit camera_RGB ≈ M · reference_XYZ (known colours under an unknown white
//                         balance); the mirror images must lose, or the chart is not accepted;
//   6. refine_corners     sub-pixel corners: patch edges located along their normals (the 50 %
//                         crossing between a patch's colour and its surround's, averaged along the
//                         edge), then the four corners (8 numbers, the homography) and the patch gap
//                         fitted to every edge point by robust Gauss-Newton (Eigen);
//   7. reference_fit_residuals  per-patch agreement with the reference after the final sampling.
// No machine-learning model; hand-written image processing is limited to box filters, a gradient,
// connected components and a convex hull.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/colorimetry/colorimetry.hpp"

namespace tristim {

struct DetectOptions {
  /// Layouts to look for (ids of chart_layout: "cc24", "cc24-2005", "passport", "sg140",
  /// "sg140-2005", "custom"). Empty: "cc24" and "sg140" (a Passport is reported as "cc24": the
  /// classic side has the same grid and colours; ask for "passport" to have it named so).
  std::vector<std::string> charts;
  /// Geometry of "custom" (rows, columns, margins, gap; `chart` is ignored).
  LayoutOptions custom;
  /// Reference colours of "custom" in layout order (row-major from A1), any linear tristimulus
  /// space (XYZ, or camera RGB of a reference shot). Empty: the orientation of a custom chart
  /// cannot be told from its colours; it is then reported with A1 nearest the image's top-left
  /// and `orientation_resolved` false.
  std::vector<Vec3> custom_reference;
  /// Longer side of the working image of steps 1-5 (the refinement uses the full image). When
  /// that finds no chart in a larger image, a coarse pass at a longer side of <= 1000 px follows
  /// (it keeps only confident candidates whose lattice holds half of the layout).
  int working_side = 1600;
  /// Help from the user (image pixel coordinates; at most one of the two):
  /// seed {x, y}, a point on or near the chart: detection runs in square windows centred on it,
  /// growing from 1/4 of the image's longer side to the whole image, and keeps the first chart
  /// found near the seed — within its grid enlarged to twice its size about its centre, or within
  /// 5 % of the image's longer side of that centre (a small chart is searched at full resolution);
  /// box {x0, y0, x1, y1}, a rough box around the chart: detection runs within it, enlarged by a
  /// tenth of its size on each side.
  std::vector<double> seed;
  std::vector<double> box;
  /// Find charts partly outside the frame (ChartCandidate::missing names the patches outside);
  /// false refuses them, as the detector did before (benchmarks compare the two).
  bool cut_charts = true;
  /// When the passes above find nothing in an image no larger than working_side (worked on at
  /// full resolution), one more on the image enlarged twice (bilinear), keeping only confident
  /// candidates whose lattice holds half of the layout or whose refined grid's edges were seen
  /// around 70 % of the patches: charts of a few % of the frame with ~10 px patches. false: as
  /// the detector did before (benchmarks compare the two).
  bool finer_pass = true;
  /// Candidates below this confidence are dropped.
  double min_confidence = 0.5;
  int max_candidates = 8;
  /// Called with a stage name ("segment", "group", "orient", "refine") and the overall fraction
  /// done, 0..1. May be empty.
  std::function<void(const std::string& stage, double fraction)> progress;
};

/// One patch's agreement with the reference: relative residual |rgb - M·ref| / (|M·ref| + 2 %
/// of the brightest prediction) after the robust 3×3 fit of the whole chart.
struct PatchAgreement {
  std::string id;
  double residual = 0;
};

struct ChartCandidate {
  std::string chart;                 ///< layout id ("cc24", "passport", "sg140", "custom", …)
  std::array<double, 8> corners{};   ///< x1,y1..x4,y4: A1's outer corner first, clockwise
  double confidence = 0;             ///< 0..1
  /// Clockwise rotation of the chart in the image, nearest multiple of 90°: the direction of
  /// A1 -> A6 (the first row) is right for 0, down for 90, left for 180, up for 270.
  int orientation = 0;
  double angle = 0;                  ///< the same direction exactly, degrees clockwise from +x
  bool orientation_resolved = true;  ///< false for a custom chart without reference colours
  double residual = 0;               ///< median per-patch residual of the 3×3 fit
  double runner_up_residual = 0;     ///< best residual of any other placement (rotation, mirror, offset)
  double gap = 0;                    ///< fitted gap between patches / patch size
  double edge_rms = 0;               ///< RMS distance of the edge points to the fitted grid, px
  int edges = 0;                     ///< edge points used by the refinement
  double coverage = 0;               ///< fraction of the layout's patches found as quads
  double supported = 0;              ///< fraction of the patches with edges on 2+ sides (refinement)
  double alternative_residual = 0;   ///< best score of the chart's other symmetric orientations at the final corners
  std::vector<PatchAgreement> patches;  ///< the patches inside the image
  /// A chart cut by the frame: the ids of the patches whose sample area lies outside the image
  /// (its corners are then extrapolated and may lie outside it; sample with
  /// SampleOptions::partial). Empty for a whole chart.
  std::vector<std::string> missing;
};

/// Finds charts. Best candidate first; several charts give several candidates. A chart partly
/// outside the frame is found when at least half of its patches are inside: its corners are
/// extrapolated (they may lie outside the image) and ChartCandidate::missing names the rest.
/// Errors: ChartNotFound (nothing above min_confidence; the message says why, about the largest
/// grid seen: "no flat region is shaped like a patch", "the largest flat regions form no grid",
/// "a grid of 4×6 found but its colours do not fit the cc24 chart (…)", a grid that runs off the
/// image border, …, then the counts of patch-like regions and grids), UnknownId (unknown chart
/// id), InvalidArgument (empty image, bad custom geometry or a custom reference of the wrong
/// length, a seed outside the image, a box holding no 16×16 px of it, both a seed and a box).
std::vector<ChartCandidate> detect_charts(const RawImage& image, const DetectOptions& options = {});

/// ChartCandidate::angle of corners in the layout convention: the direction A1 -> A6 (corner 1 ->
/// corner 2), degrees clockwise from +x (y down), in [0, 360); within 0.005° below 360 it is 0.
double chart_angle(const std::array<double, 8>& corners);

/// Candidates as JSON `{"candidates": [{"chart", "corners": [[x,y]×4], "confidence",
/// "orientation", "angle", "orientation_resolved", "residual", "gap", "edge_rms", "patches":
/// [{"id", "residual"}], "missing": [ids]}]}`.
std::string candidates_to_json(const std::vector<ChartCandidate>& candidates);

// ================================================================ the steps

/// Step 1. Box-downsampled copy (mean of factor × factor blocks; saturation bits OR-ed); the
/// factor is ceil(max(width, height) / working_side), at least 1. Pixel (x, y) of the result
/// covers [x·f, (x+1)·f) of the input.
RawImage working_image(const RawImage& image, int working_side, int* factor = nullptr);

/// Step 2a. Pixel noise of the working image per channel, σ² = gain·I + floor (shot and read
/// noise), fitted to the MAD of I(x) - (I(x-1) + I(x+1))/2 in 24 brightness bins of equal count
/// (bins dominated by texture are down-weighted).
struct NoiseModel {
  std::array<double, 3> gain{}, floor{};
};
NoiseModel estimate_noise(const RawImage& working);

/// Step 2. Connected regions (4-connected) of "flat" pixels: in every channel, half the central
/// differences of log(RGB + ε) of the 3×3-box-smoothed image stay below `noise_multiple` times
/// their noise (from estimate_noise) or `min_step` (log units), whichever is larger. The mask
/// is eroded once (3×3) so neighbours joined by a thin bridge come apart.
struct RegionLabels {
  int width = 0, height = 0;
  std::vector<int> label;  ///< width*height, -1 outside every region
  int count = 0;
};
struct FlatRegionOptions {
  double noise_multiple = 4.0;
  double min_step = 0.01;
};
RegionLabels flat_regions(const RawImage& working, const FlatRegionOptions& options = {});

/// Step 3. A region kept as a patch: its pixels fill ≥ 85 % of the largest quadrilateral fitted
/// to its convex hull (support points in four perpendicular directions), which holds ≥ 80 % of
/// the hull; not touching the border; min_pixels..max_fraction of the image.
struct PatchQuad {
  std::array<Eigen::Vector2d, 4> corners;  ///< clockwise in image coordinates (y down)
  Eigen::Vector2d centre;                  ///< mean of the region's pixel centres
  Eigen::Vector2d side_a, side_b;          ///< mean opposite-side vectors (corner 0->1, 0->3)
  double area = 0;                         ///< pixels
  Vec3 mean = Vec3::Zero();                ///< mean linear RGB of the region
};
struct QuadOptions {
  int min_pixels = 16;
  double max_fraction = 0.05;
};
std::vector<PatchQuad> patch_quads(const RawImage& working, const RegionLabels& regions,
                                   const QuadOptions& options = {});

/// Step 4. A lattice of quads: integer cell (p, q) -> quad, and the homography lattice -> image
/// (image point of the cell centre (p, q) = H · (p, q, 1)), fitted to the quads' centres.
struct GridGroup {
  std::vector<std::array<int, 2>> cells;  ///< (p, q) per member
  std::vector<int> quads;                 ///< index into the quad list, same order as cells (-1: group_regions)
  Eigen::Matrix3d lattice_to_image = Eigen::Matrix3d::Identity();
  int p_min = 0, p_max = 0, q_min = 0, q_max = 0;
};
/// Groups with at least `min_cells` members, largest first. Each quad joins one group at most.
std::vector<GridGroup> group_grids(const std::vector<PatchQuad>& quads, int min_cells = 4);

/// Step 4, for charts of small patches without a gap (a Digital SG of a few % of the frame, in
/// the finer pass of DetectOptions::finer_pass): lattices grown from single quads into flat
/// regions that are not quads. Noise and blur leave such a patch a ragged flat interior that
/// patch_quads refuses (a Digital SG of 3 % of 1200 × 800 tilted 37°: 27 of 140 kept, no two
/// of them neighbours), but its centre still marks the cell. A quad gives the lattice axes; the
/// nearest region along each axis, the pitch; then every cell within two of a member whose
/// predicted centre lies in a region that can be one patch of it (centre within 0.3 cell, extent
/// within one pitch along each axis, fewer pixels than the cell) joins, and the lattice -> image
/// map is refitted (affine, then a homography) to the regions' centres, as in group_grids.
/// GridGroup::quads holds -1 for a member that is not a quad. Groups with at least `min_cells`
/// members, largest first; each region joins one group at most.
std::vector<GridGroup> group_regions(const std::vector<PatchQuad>& quads, const RegionLabels& regions, int min_cells = 4);

/// Step 5. One placement of a layout on a lattice: layout cell (row r, column c) sits at lattice
/// cell D·(c, r) + offset, D one of the 8 symmetries of the square (transform 0-3: rotations by
/// 0/90/180/270° in lattice coordinates, 4-7: the same after a mirror).
struct Placement {
  int transform = 0;
  std::array<int, 2> offset{};
  bool mirrored = false;         ///< the chart -> image map reverses orientation (impossible physically)
  bool inside = true;            ///< every cell centre lies in the image
  double residual = 1e9;         ///< trimmed mean relative residual of the 3×3 fit (see PatchAgreement)
  int found = 0;                 ///< layout cells that hold one of the group's quads
  std::array<double, 8> corners{};  ///< patch-grid corners (layout convention) in working-image pixels
};
/// Every placement whose window holds ≥ 50 % of the group's cells, best (lowest residual) first.
/// `reference`: one colour per layout patch (row-major), or empty (residuals then all 0).
std::vector<Placement> place_layout(const RawImage& working, const GridGroup& group, const ChartLayout& layout,
                                    const std::vector<Vec3>& reference);

/// Step 6. Sub-pixel corners by fitting the layout's patch edges. `corners` is the initial
/// estimate (layout convention), `search_px` how far from the predicted edge to look. With
/// `fit_gap` the gap between patches (fraction of the patch size) is fitted too, starting from
/// layout.gap. Corners are unchanged when too few edges are found (edges < 8).
struct Refinement {
  std::array<double, 8> corners{};
  double gap = 0;
  double rms = 0;     ///< RMS distance of the inlier edge points to their fitted edges, px
  int edges = 0;      ///< edge points used
  int inliers = 0;    ///< of which within 3 robust σ
  double supported = 0;  ///< fraction of the patches with edge points on 2 or more sides
};
Refinement refine_corners(const RawImage& image, const LayoutOptions& layout,
                          const std::array<double, 8>& corners, double search_px, bool fit_gap);

/// Step 7. Robust 3×3 fit camera_RGB ≈ L · M · reference (least squares weighted to relative
/// errors, refitted without the worst 25 %): the per-patch relative residuals (see
/// PatchAgreement), same order as the inputs. With `positions` (each patch's centre in the
/// chart, 0..1 across the grid) the light L may vary over the chart, fitted alternately with M:
/// smoothly — vignetting, a lamp to one side: log L linear in (u, v) from 12 patches, quadratic
/// from 24, each factor within 0.5..2 — and, from 12 patches, by a step across a straight line
/// (a cast shadow's edge: the half-plane split of the patches that best explains their light,
/// kept when it explains most of its variation, 4 patches or more on each side; docs/detection.md).
/// `unreliable` (empty, or one flag per pair): patches whose sample is clipped or not uniform
/// (glare, a shadow's edge across them: reference_fit_nonuniform) are left out of the fit when
/// they are at most a third of the pairs and 6 others remain; their residuals are still returned.
/// Glare (with `unreliable`): on the flagged patches and their grid neighbours a highlight may add
/// the illuminant's colour, camera_RGB ≈ M · (L · reference + g · white), g ≥ 0 fitted per patch
/// (white: the reference's brightest colour); the residuals returned keep the glare (a highlight
/// shows), `glare_free` (optional) receives them with it taken off (docs/detection.md).
/// Needs ≥ 4 pairs.
std::vector<double> reference_fit_residuals(const std::vector<Vec3>& camera_RGB, const std::vector<Vec3>& reference,
                                            const std::vector<Eigen::Vector2d>& positions = {},
                                            const std::vector<bool>& unreliable = {},
                                            std::vector<double>* glare_free = nullptr);

/// A patch sample is unreliable for the fit when its four quadrant means differ by more than this
/// fraction of its mean (and by 4 standard errors: SampleOptions::nonuniform_threshold's test),
/// or a pixel of it is clipped.
inline constexpr double reference_fit_nonuniform = 0.25;

/// The same fit summarised: mean of the smallest 75 % of the glare-free residuals
/// (Placement::residual), the patches left out of the fit dropped first (beyond a quarter of the
/// pairs, theirs count).
double reference_fit_score(const std::vector<Vec3>& camera_RGB, const std::vector<Vec3>& reference,
                           const std::vector<Eigen::Vector2d>& positions = {},
                           const std::vector<bool>& unreliable = {});

/// reference_fit_score without the glare model and with it (`glare` = `plain` when it does not
/// apply: no patch flagged, or a chart of more than 48 patches). Needs ≥ 4 pairs.
struct FitScores {
  double plain = 0, glare = 0;
};
FitScores reference_fit_scores(const std::vector<Vec3>& camera_RGB, const std::vector<Vec3>& reference,
                               const std::vector<Eigen::Vector2d>& positions = {},
                               const std::vector<bool>& unreliable = {});
/// Which model ranks a set of rival fits of one lattice (its placements; or the fit `chosen` and
/// its symmetric alternatives): the glare model when it halves the best score and sets the best
/// (or `chosen`) fit further from the best other one than the plain fit does. Decided once per
/// set, never per fit: the glare model lowers a wrong placement's score too.
bool rank_with_glare(const std::vector<FitScores>& rivals, int chosen = -1);

/// Helpers shared by the steps: a DLT homography (Hartley-normalised, Eigen SVD) mapping
/// src[i] -> dst[i] (≥ 4 points), and applying one.
Eigen::Matrix3d fit_homography(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst);
inline Eigen::Vector2d apply_homography(const Eigen::Matrix3d& H, const Eigen::Vector2d& p) {
  const Eigen::Vector3d q = H * Eigen::Vector3d(p.x(), p.y(), 1.0);
  return q.head<2>() / q.z();
}

}  // namespace tristim

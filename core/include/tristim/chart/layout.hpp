// tristim — colour chart layouts and patch sampling on a linear RAW image.
//
// Geometry: the user gives the four corners of the chart's patch grid, clockwise from the
// top-left (the outer corner of patch A1), in measurement-image coordinates: pixel (x, y) of
// RawImage covers [x, x+1) × [y, y+1), so the image spans [0, width] × [0, height] (for a
// Bayer sensor these are half-resolution coordinates). A homography (DLT, eq. of Hartley &
// Zisserman) maps the unit square of chart coordinates (u right, v down, (0,0) = top-left corner)
// onto those four points. The patches form a rows × columns grid with gaps between them (no gap
// outside: the corners are the outer corners of the corner patches); the sampled area is the
// patch's central `area` fraction of its width and of its height (0.5 = the middle half of each
// side, a quarter of the patch area: "averaging the central area", Abed et al. 2013 App. C step 3).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/capture/raw.hpp"
#include "tristim/io/fields.hpp"

namespace tristim {

struct FrameCalibration;  // calibration.hpp

/// Which grid to lay over the corners.
struct LayoutOptions {
  /// "cc24" / "cc24-2005" (ColorChecker Classic 6×4, ids A1..D6: row letter A-D top to bottom,
  /// column 1-6), "passport" (Passport classic side, same ids as cc24), "sg140" / "sg140-2005"
  /// (ColorChecker SG 14×10, ids A1..N10: letter = COLUMN A-N, number = ROW 1-10), "custom"
  /// (rows × columns, ids R1C1..).
  std::string chart = "cc24";
  int rows = 0, columns = 0;   ///< custom only
  /// Custom only: margins between the given corners and the patch grid, as fractions of the
  /// chart's width (left, right) and height (top, bottom).
  double margin_left = 0, margin_top = 0, margin_right = 0, margin_bottom = 0;
  /// Gap between neighbouring patches as a fraction of the patch size; negative = the chart's
  /// default (0.14 for cc24/passport, 0 for sg140 and custom).
  double gap = -1;
};

struct PatchCell {
  std::string id;
  int row = 0, column = 0;     ///< 0-based grid position
  double u0 = 0, v0 = 0, u1 = 0, v1 = 0;  ///< the patch in chart coordinates (unit square)
};

struct ChartLayout {
  std::string chart;
  int rows = 0, columns = 0;
  double gap = 0;
  std::vector<PatchCell> patches;  ///< row-major from the top-left
};

/// The built-in or custom layout. UnknownId for an unknown chart; InvalidArgument for bad
/// custom sizes or margins.
ChartLayout chart_layout(const LayoutOptions& options);

/// Ids of the built-in charts ("cc24", "cc24-2005", "passport", "sg140", "sg140-2005", "custom").
std::vector<std::string> chart_layout_ids();

/// 3×3 homography H (row-major) with [x y 1]^T ~ H [u v 1]^T mapping the unit square's corners
/// (0,0), (1,0), (1,1), (0,1) to corners[0..3] = (x1,y1)...(x4,y4). DLT solved with Eigen's SVD.
std::array<double, 9> homography_unit_square(const std::array<double, 8>& corners);

/// Checks the corners against a width × height image: CornersOutside if any lies outside
/// [0, width] × [0, height] (with `may_leave_image`: only if one is not finite); CornersCrossed
/// if the quadrilateral is self-intersecting, degenerate, not convex or counter-clockwise
/// (mirrored: corners must go clockwise from A1).
void check_corners(const std::array<double, 8>& corners, int width, int height, bool may_leave_image = false);

struct SampleOptions {
  double area = 0.5;              ///< sampled fraction of the patch's width and height, (0, 1]
  int min_pixels = 4;             ///< fewer pixels in a patch: PatchTooSmall
  /// "dark" when a channel's mean is below dark_fraction × that channel's saturation level (or
  /// below 3 × the noise floor of an applied dark frame, whichever is larger).
  double dark_fraction = 0.002;
  /// "nonuniform" when, in a channel that is not dark, the means of the sample area's four
  /// quadrants differ by more than this fraction of the patch mean and by more than 4 standard
  /// errors (a gradient, glare, dust or a patch border in the sample area). Pixel noise alone —
  /// a large σ on a flat patch, as in a dim photo — does not flag: its mean is still precise.
  double nonuniform_threshold = 0.05;
  /// A chart cut by the frame: the corners may lie outside the image (they must still go
  /// clockwise and be convex); a patch whose sample area is not wholly inside the image is left
  /// out of ChartSample::patches and named in ChartSample::missing. CornersOutside when none is.
  bool partial = false;
};

struct PatchSample {
  std::string id;
  std::array<double, 3> mean{};        ///< linear camera RGB, black (and dark) subtracted, DN
  std::array<double, 3> std{};         ///< sample standard deviation over the patch's pixels
  int n = 0;                           ///< pixels averaged (every pixel of the sample area)
  std::array<double, 3> saturated_fraction{};  ///< fraction of those pixels clipped per channel
  std::vector<std::string> flags;      ///< "saturated", "dark", "nonuniform"
  std::array<double, 2> centre{};      ///< patch centre in image coordinates
  std::array<double, 8> quad{};        ///< the patch's corners in the image (TL, TR, BR, BL; x, y)
  std::array<double, 8> sample_quad{}; ///< the sampled area's corners in the image
};

struct ChartSample {
  ChartLayout layout;
  std::array<double, 9> homography{};
  std::vector<PatchSample> patches;  ///< layout order; with SampleOptions::partial only the visible ones
  std::vector<std::string> missing;  ///< ids of the patches outside the image (SampleOptions::partial)
};

/// Samples every patch of `layout` placed by `corners` (see the header comment). Saturated
/// pixels are counted in the mean and reported per channel; any saturated pixel flags the
/// patch "saturated" (never silently averaged). With `calibration` the pixel values are
/// dark-subtracted / flat-fielded on the fly (calibration.hpp). Errors: CornersOutside,
/// CornersCrossed, PatchTooSmall, InvalidArgument (area outside (0, 1]).
ChartSample sample_chart(const RawImage& image, const LayoutOptions& layout,
                         const std::array<double, 8>& corners, const SampleOptions& options = {},
                         const FrameCalibration* calibration = nullptr);

/// CSV `patch,R,G,B,R_std,G_std,B_std,n,flags` (flags joined with ';'), one row per patch.
std::string chart_sample_to_csv(const ChartSample& sample);

}  // namespace tristim

// Its field list (defined in profile/recipe.cpp, beside the recipe's sampling stage that holds it):
// the JSON, the CLI and the wasm binding use it — the margins as one array [left, top, right, bottom].
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(LayoutOptions);
}  // namespace tristim::fields

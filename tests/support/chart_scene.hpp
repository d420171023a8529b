// tristim — synthetic photographs of colour charts for the detection tests (issue 12).
//
// A chart's patches are rendered by the virtual camera (simulate/virtual_camera.hpp: real camera
// sensitivities × the chart's measured reflectances × an illuminant), placed on a plane tilted
// in 3D and projected with a pinhole camera (so the chart -> image map is an exact homography),
// drawn over a background (a synthetic one with distracting shapes, or a crop of a real photo),
// then lit unevenly (vignetting, a gradient, glare on some patches), blurred, exposed to a
// 14-bit-like range with shot and read noise, and clipped. The truth — the patch grid's four
// corners in the convention of chart/layout.hpp — comes with every image. Everything is drawn
// from one seed with a portable generator (mt19937_64 bits, no std distributions), so native and
// wasm builds make the same images.
#pragma once
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tristim/capture/raw.hpp"
#include "tristim/chart/detect.hpp"

namespace tristim {

struct SceneSpec {
  std::string chart = "cc24";     ///< "cc24", "passport" (with the creative side above) or "sg140"
  int width = 1200, height = 800;
  std::string camera = "Canon_EOS_5D_Mark_II";
  std::string illuminant = "D65";
  double area_fraction = 0.2;     ///< patch-grid area / image area (before fitting it in)
  double tilt_deg = 0;            ///< tilt of the chart plane away from the camera
  double tilt_axis_deg = 0;       ///< direction of the tilt axis in the chart plane
  double rotation_deg = 0;        ///< in-plane rotation, clockwise on screen
  double focal = 3;               ///< camera distance in chart heights (smaller = stronger perspective)
  double cx = 0.5, cy = 0.5;      ///< grid centre as a fraction of the image size
  double gap = -1;                ///< gap / patch size; < 0: the layout's default (0 for the SG)
  double exposure = 0.4;          ///< white's G as a fraction of saturation
  double shot_gain = 1, read_noise = 3;  ///< noise: σ² = shot_gain·DN + read_noise²
  double blur_sigma = 0.7;        ///< Gaussian blur, px
  double vignetting = 0.2;        ///< light fall-off at the image corners (fraction)
  double gradient = 0.1;          ///< linear light gradient across the image (fraction)
  int glare_patches = 0;          ///< patches with a specular highlight
  double glare_strength = 1;      ///< highlight peak in units of the white patch
  double shadow = 0;              ///< a cast shadow across the chart: light lost in it (0..1), soft edge
  bool grid_object = false;       ///< a grid-like object beside the chart (4×5 tiles of other colours, same plane)
  bool phone = false;             ///< phone-like output: white balanced, sRGB-encoded, noise-reduced,
                                  ///< sharpened, 8-bit (stored values 0..255, as a decoded JPEG)
  bool photo_background = false;  ///< background from `photos` (else synthetic)
  bool allow_cut = false;         ///< do not shrink the chart into the frame
  std::uint64_t seed = 1;         ///< texture, shapes, glare positions and noise
};

struct ChartScene {
  RawImage image;
  std::array<double, 8> corners{};  ///< truth: patch grid corners, A1's first, clockwise
  SceneSpec spec;
  double area_fraction = 0;         ///< the grid's area / image area as rendered
  bool cut = false;                 ///< a grid corner lies outside the image
  std::array<double, 3> white{};    ///< DN of a perfect white at the image centre (for display)
};

/// Renders one scene. `photos`: linear images to crop backgrounds from (used when
/// spec.photo_background; any empty image is skipped).
ChartScene render_chart_scene(const SceneSpec& spec, const std::vector<const RawImage*>& photos = {});

/// Draws every parameter of SceneSpec at random from `seed` (chart and size given): grid area
/// 3 %-90 % of the frame (log-uniform), tilt up to 45°, any rotation, perspective, one of 52
/// cameras and six illuminants, exposure 5-80 %, noise, blur 0.3-2 px, vignetting up to 50 %,
/// glare on up to two patches (40 % of scenes), a photo background in half the scenes.
SceneSpec random_scene_spec(const std::string& chart, std::uint64_t seed, int width, int height, bool photos);

/// Real photos decoded (LibRaw) for backgrounds: the Canon 30D landscape, the Kodak DC50 city, and
/// the Passport DNG's top rows (its creative side, without the classic side); test_files.hpp names
/// them, `source_dir` is the checkout. A missing file throws Error naming it.
std::vector<RawImage> background_photos(const std::string& source_dir);

/// How a detection compares with a scene's truth. Corner error: mean distance of the four
/// corners in the reported order; `located`: some cyclic order of the corners is within a
/// quarter of a patch pitch of the truth (the right place); `oriented`: that order is the
/// reported one (A1 where it should be).
struct DetectionScore {
  bool detected = false, located = false, oriented = false;
  double corner_error = 0;   ///< px, reported order
  double pitch = 0;          ///< px, mean patch pitch of the truth
  double confidence = 0;
};
DetectionScore score_detection(const ChartScene& scene, const std::array<double, 8>* corners, double confidence);

/// Two charts in one frame (issue 12: several charts give several candidates): the scene `large`,
/// and over it the part of the scene `small` (rendered at the same size) around its chart — the
/// chart's board with a margin. `ok` is false when the two boards would overlap. Each scene's
/// `corners` is a truth in `image`; their own images are dropped.
struct TwoChartScene {
  RawImage image;
  ChartScene large, small;
  bool ok = false;
};
TwoChartScene render_two_chart_scene(const SceneSpec& large, const SceneSpec& small,
                                     const std::vector<const RawImage*>& photos = {});

/// A random two-chart scene from `seed`: a chart of 10-30 % of the frame on the left (any of the
/// three layouts, `large_chart`) and a ColorChecker Classic or Digital SG of 3-6 % on the right,
/// both drawn as by random_scene_spec (tilt, rotation, light, noise, blur, glare) under one camera,
/// illuminant and exposure; the large chart shrinks until the two do not overlap.
TwoChartScene random_two_chart_scene(const std::string& large_chart, const std::string& small_chart,
                                     std::uint64_t seed, int width, int height,
                                     const std::vector<const RawImage*>& photos = {});

/// The kinds of scene detection is known to find hard (issue 48), one id each: "tilted-glare",
/// "tilted-shadow", "tilted-grid" (large charts, 30-40 % of the frame, tilted 25-33° out of
/// plane, with a strong glare spot, a cast shadow or a grid-like object beside them;
/// "tilted-glare-shadow": glare spots and a cast shadow on the same chart), "small"
/// (2-3.5 % of the frame), "passport-open" (both sides of a Passport), "cut" (the chart runs
/// off the frame), "perspective" (tilted 35-50° seen from close), "phone-jpeg" (phone-like
/// 8-bit sRGB, sharpened, noise-reduced), "sg" (ColorChecker Digital SG, as random_scene_spec)
/// and "no-chart" (nothing to find: any candidate is a false positive).
const std::vector<std::string>& failure_kinds();
/// Scene `index` of a kind: random_scene_spec's draw from `seed`, then the kind's own ranges;
/// the chart cycles through cc24, passport and sg140 where the kind allows.
SceneSpec failure_kind_spec(const std::string& kind, int index, std::uint64_t seed, int width, int height, bool photos);

/// Figures of one kind: automatic detection, and detection helped by one click (DetectOptions::
/// seed at a point within a quarter of the grid's size of its centre) on the scenes it missed.
struct KindFigures {
  std::string kind;
  int n = 0;
  int found = 0;              ///< at the right place in the right orientation (DetectionScore::oriented)
  int wrong_orientation = 0;  ///< at the right place, wrong orientation
  int false_positives = 0;    ///< confident candidates away from the chart (every one for no-chart)
  int found_with_click = 0;   ///< found, or found after the click
  std::vector<double> errors; ///< corner error of the found ones, px
  std::vector<double> ms;     ///< time of the automatic detection
  std::vector<std::string> why;  ///< the detector's reason per miss
};
/// Renders and detects `count` scenes of each kind (`kinds` empty: all) at width × 2/3 width.
/// `verbose`: one line per scene on stdout. `base`: the detector's options (its charts are set
/// per scene), e.g. cut_charts false for the figures before issue 48's cut-chart step.
std::vector<KindFigures> run_failure_kinds(const std::vector<std::string>& kinds, int count, std::uint64_t seed,
                                           int width, const std::vector<const RawImage*>& photos, bool verbose,
                                           const DetectOptions& base = {});
/// The table of run_failure_kinds: kind, n, found, wrong orientation, false positives, corner
/// error median/p95, found with a click, median ms; then a "KIND <id> <found> ..." line per kind.
void print_failure_kinds(const std::vector<KindFigures>& figures);

/// A plain scene for the unit tests: 900 × 600, the grid 15 % of the frame, tilted 12° about an
/// axis at 30°, rotated `rotation`° in plane, blur 0.8 px, the rest SceneSpec's defaults.
SceneSpec plain_scene_spec(const std::string& chart, double rotation, std::uint64_t seed);

/// Largest distance between corresponding corners of two corner lists (x1,y1..x4,y4), px.
double max_corner_error(const std::array<double, 8>& a, const std::array<double, 8>& b);

/// Portable uniform [0, 1) from mt19937_64 (53 bits).
class SceneRandom {
 public:
  explicit SceneRandom(std::uint64_t seed);
  double uniform();
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  int integer(int n);  ///< 0..n-1

 private:
  std::mt19937_64 engine_;
};

}  // namespace tristim

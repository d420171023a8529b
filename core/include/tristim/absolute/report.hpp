// The one report of the absolute tele-colorimeter (Guarnera, Bianco & Schettini 2018): what
// `tristim absolute evaluate` prints (JSON with --json, text without) and the page shows.
//
//   fit       the profile: eq (8) per channel (k1, k2, k3 and how well they fit), the reciprocity
//             check per exposure, eq (7)'s n, S, areas and f(r), the colour matrix (eqs 11-15)
//   training  the chain on its own training stimuli (white: E at their largest Y)
//   test      a test scene: per-point rows (per-patch R, G, B through eqs 7, 8, 10, 4) and
//             per-region rows (the mean X, Y, Z of the region's central half on the fused maps),
//             section 4.1 figures — ΔE94, ΔE00 (CIELAB relative to the eq 16 white), NRMSE per X,
//             Y, Z, the relative Y error and the median absolute error — over every row, then
//             over the chromatic and the equal-tristimulus rows apart when both are present
//   maps      the exposure selection: which exposure served how many pixels, Y's range
// JSON: every double with 17 significant digits (non-finite: null), so the page and the CLI can
// be compared to the bit.
#pragma once
#include <string>
#include <vector>

#include "tristim/absolute/profile.hpp"

namespace tristim {

struct AbsoluteChannelFit {
  double k1 = 0, k2 = 1, k3 = 1;  ///< eq (8), exposure units relative to iso_reference
  int samples = 0;
  double rms_relative = 0, max_relative = 0, r_squared = 0;
  std::string message;
};

/// The reciprocity check of one {t, N, ISO} (luminance.hpp's ExposureReport, without its curves).
struct AbsoluteExposureCheck {
  ExposureSettings exposure;
  std::string label;                 ///< "1/60 s f/8 ISO 100"
  double factor = 0;                 ///< ε relative to the reference ISO
  bool parallel = true;
  std::array<int, 3> samples{};
  std::array<double, 3> scale_ratio{}, slope_difference{}, rms_relative{};
};

struct AbsoluteFitSummary {
  std::string make, model;
  int width = 0, height = 0;
  std::array<AbsoluteChannelFit, 3> channels;
  double iso_reference = 0;
  bool reciprocity_ok = true;
  std::string reciprocity_message;
  std::vector<AbsoluteExposureCheck> exposures;  ///< shortest first
  std::array<double, 3> noise_floor{}, noise_sigma{}, saturation{}, saturation_reported{}, saturation_fraction{}, areas{};
  std::array<bool, 3> saturation_measured{};
  std::string areas_source;
  bool has_falloff = false;
  FalloffFit falloff;
  double w = 10;
  std::string transform, colour_status, colour_message;
  Eigen::MatrixXd colour_matrix;  ///< M, 3 × P
  int colour_stimuli = 0;
  double colour_objective = 0;    ///< eq (11) at the optimum, cd/m²
  std::string fusion;
};
AbsoluteFitSummary absolute_fit_summary(const AbsoluteProfile& profile);

/// One stimulus of a test scene and its estimate.
struct AbsoluteTestRow {
  std::string id, set;                   ///< set: luminance | colour (completed)
  std::string file;                      ///< region rows: the frame named ("": per patch)
  int x = 0, y = 0, w = 0, h = 0;
  int pixels = 0;                        ///< region: finite pixels averaged (its central half)
  bool saturated = false;                ///< per patch: a channel in the saturated zone (left out)
  Vec3 estimated = Vec3::Constant(NAN);  ///< cd/m²
  Vec3 reference = Vec3::Zero();         ///< cd/m²
  double relative_Y_error = NAN;         ///< (Y_est − Y_ref)/Y_ref
  int source = -1;                       ///< region: dominant exposure at its centre (−1: none)
  std::string source_label;
};

/// Section 4.1 figures over a group of test rows.
struct AbsoluteFigures {
  std::string group;  ///< "all" | "colour" | "luminance"
  std::string label;  ///< "every stimulus", "chromatic", "equal-tristimulus"
  int count = 0;
  AbsoluteMetrics metrics;
};

struct AbsoluteTestReport {
  std::string white_rule;     ///< "eq16": the white patch scaled to Y_Q; "E": X = Y = Z = Y_Q
  std::string white_id;       ///< eq16: the test stimulus taken as the white patch
  double max_luminance = 0;   ///< Y_Q: the largest reference Y of the scene, cd/m²
  Vec3 white = Vec3::Zero();  ///< the CIELAB white of the figures, cd/m²
  std::vector<AbsoluteTestRow> points, regions;
  std::vector<AbsoluteFigures> figures;  ///< "all" first
};

/// The exposure selection over the maps.
struct AbsoluteMapsSummary {
  int width = 0, height = 0;
  std::string mode;                       ///< weighted | recursive
  std::vector<ExposureSettings> exposures;
  std::vector<std::string> labels;        ///< per exposure, in the order the frames were given
  std::vector<std::string> names;         ///< the frames' files
  std::vector<double> dominant_pixels;    ///< per exposure
  double saturated_pixels = 0, unreliable_pixels = 0, finite_pixels = 0;
  Summary Y;                              ///< over finite pixels, cd/m²
  double Y_p01 = NAN, Y_p99 = NAN;        ///< 1st and 99th percentile (evaluation's quantile)
};

struct AbsoluteReport {
  AbsoluteFitSummary fit;
  bool has_training = false;
  AbsoluteTraining training;
  bool has_test = false;
  AbsoluteTestReport test;
  bool has_maps = false;
  AbsoluteMapsSummary maps;
};

/// A choice of the CIELAB white of a test scene's figures as the page's picker lists it (the CLI's
/// --white): "" the brightest chromatic stimulus as the white patch (eq 16), "E" X = Y = Z at the
/// largest Y; a stimulus id names the white patch itself.
struct AbsoluteWhiteRule {
  std::string id, label, reference;
};
std::vector<AbsoluteWhiteRule> absolute_white_rules();

json::Value absolute_report_json(const AbsoluteReport& report);
/// The same report as readable text (the CLI without --json).
std::string absolute_report_text(const AbsoluteReport& report);

}  // namespace tristim

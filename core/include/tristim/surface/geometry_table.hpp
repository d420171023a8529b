// Abed, Berns & Masaoka 2013 Table IV: five characterisation methods trained on one chart and
// tested on another chart seen in the capture geometry — and a simulation of that experiment
// with the virtual camera, since no capture-geometry measurements of a real chart are at hand.
//
// Methods (columns of Table IV):
//   scaler-offset   Phase II joint fit, eq (5) + anchored 3×3 (joint.hpp)
//   saunderson      Phase II joint fit, eq (3) with the instrument's coefficients fixed + anchored 3×3
//   matrix-3x3      least squares RGB -> instrument XYZ (eq 7 without offsets)
//   matrix-3x4      least squares RGB -> instrument XYZ with offsets (eqs 6, 26)
//   corrected-3x3   the 3×4 without its offset, scaled by μ from the white (eqs 6-13, App. C)
// Errors on the test chart: mean and max over patches of ΔE_xyz (Euclidean XYZ distance with the
// white at Y = 1, the scale of the paper's Table IV) and of CIEDE2000 (Lab relative to the
// illuminant's white).
//
// Simulation (simulate_geometry_chart): a chart's spectra are taken as what the instrument reports
// in its geometry; eq (2) with the chart's measurement coefficients gives the internal
// reflectance (clamped at 0 where a spectrum lies below the instrument's specular floor
// k_ins·k1, so the instrument then reads that floor); eq (1) with the measurement coefficients
// gives what the instrument reads, eq (1) with the capture coefficients what the camera sees. The
// virtual camera (simulate/virtual_camera.hpp) renders the latter; the white reference is a
// Lambertian R_w in every geometry.
#pragma once
#include <string>
#include <vector>

#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/methods.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "tristim/surface/saunderson.hpp"

namespace tristim {

/// A chart for the table: camera RGB in the capture geometry and, for training, the instrument's
/// reflectances; for testing, the XYZ of what the camera sees (the truth).
struct GeometryChart {
  std::string name;
  std::vector<std::string> ids;
  PatchMatrix camera_RGB;   ///< N × 3, linear
  SpectralData measured;    ///< the instrument's reflectance factors (training)
  SpectralData seen;        ///< the capture-geometry reflectance factors (simulation only)
  PatchMatrix seen_XYZ;     ///< XYZ (Y = 100) of `seen`: the test truth
};

struct GeometryScene {
  SpectralData ssf;                         ///< camera sensitivities (camera_ssf)
  SpectralData illuminant;                  ///< empty: D50
  Observer observer = Observer::CIE1931_2;
  SimulationOptions camera;                 ///< noise, seed ... (white_level: G of the perfect diffuser)
  double white_reflectance = 0.99;          ///< the white reference (pressed PTFE)
};

/// Renders `spectra` (instrument reflectances, fractions) as described above.
GeometryChart simulate_geometry_chart(const std::string& name, const SpectralData& spectra,
                                      const SaundersonGeometry& measurement, const SaundersonGeometry& capture,
                                      const GeometryScene& scene);
/// Camera RGB of the white reference (a flat R_w) in the scene.
Vec3 simulate_white_RGB(const GeometryScene& scene);
/// Two charts as one training set (e.g. the paper's "Total"); ids prefixed by the chart names.
GeometryChart combine_charts(const std::string& name, const GeometryChart& a, const GeometryChart& b);

struct GeometryTableOptions {
  SpectralData illuminant;                  ///< empty: D50
  Observer observer = Observer::CIE1931_2;
  Vec3 white_RGB = Vec3::Zero();            ///< camera RGB of the white reference
  double white_reflectance = 0.99;
  /// Start (and fixed instrument coefficients) of the Saunderson joint fit.
  MethodChoice saunderson{"saunderson", {}, {}};
};

/// One cell of Table IV.
struct GeometryTableCell {
  std::string training, method;   ///< training chart name; method id as listed above
  bool ok = false;
  std::string error_code, message;
  Summary dE_xyz, dE00;           ///< on the test chart (ΔE_xyz with Y_white = 1)
  Mat3 matrix = Mat3::Zero();     ///< RGB -> XYZ (Y = 100) used on the test chart
  MethodChoice correction{"none", {}, {}};  ///< the fitted correction (joint methods)
  double mu = 0;                  ///< corrected-3x3: eq (12)
  std::string status;             ///< the joint fit's status
};

/// The method ids of Table IV, in the paper's column order.
std::vector<std::string> geometry_table_methods();
/// Every training chart × method, tested on `test` (its camera_RGB and seen_XYZ).
std::vector<GeometryTableCell> geometry_table_Abed2013(const std::vector<GeometryChart>& training,
                                                       const GeometryChart& test, const GeometryTableOptions& options);

/// The simulated experiment the tests, the example and the page run: camera `camera`
/// (virtual_camera.hpp names), illuminant `illuminant_id`, noise σ (white G = 1; the noise row of
/// surface_option_table(), Error(InvalidArgument) outside it).
/// Instrument: 45°:0° (Eye-one); capture: diffuse booth — the coefficients of the paper's
/// Table III: training "Classic" = cc24-2005 spectra with the Classic row (matte), "SG" =
/// sg140-2005 with the SG row (semi-gloss), "Glossy" = sg140 with the Custom-Glossy row, "Total" =
/// Classic + SG; test = cc24 spectra with the Custom-Matte row (a matte chart). The Saunderson fits
/// fix the instrument to the "45-0" preset (not to the truth).
struct GeometryExperiment {
  GeometryScene scene;
  std::vector<GeometryChart> training;
  GeometryChart test;
  GeometryTableOptions options;
};
GeometryExperiment geometry_experiment_Abed2013(const std::string& camera = "Nikon_D850",
                                                const std::string& illuminant_id = "D50", double noise_sigma = 0.001,
                                                uint64_t seed = 1);

}  // namespace tristim

// The field list (io/fields.hpp; defined in surface/fields.cpp) of a cell as `tristim surface table4
// --json` prints it under "cells" and the module's surfaceTable4 gives it: training, method, ok,
// error_code (only when not ok), message, dE_xyz, dE00 (Summary's list), surface (the fitted
// correction as a --surface value; read back by parse_choice), mu (corrected-3x3 only), status.
// The matrix stays in C++.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(GeometryTableCell);
}  // namespace tristim::fields

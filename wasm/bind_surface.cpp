// Declarations: the surface stage (Abed, Berns & Masaoka 2013) — the Saunderson presets, a
// correction applied to reflectances, Phase I (one measurement onto another), Phase II (jointly
// with a white-anchored 3×3), the corrected 3×3 (eqs 6-13) and the simulated Table IV. The table
// of corrections itself is listSurfaceCorrections (bind_catalog.cpp). Illuminants cross as ids. The
// results (SurfaceFitResult, JointFitResult, GeometryTableCell) cross by their field lists (the
// objects `tristim surface fit / joint / table4 --json` prints; core/src/surface/fields.cpp).
#include "tristim/surface/fit.hpp"
#include "tristim/surface/geometry_table.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/options_table.hpp"
#include "tristim/surface/saunderson.hpp"
#include "tristim/surface/surface.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

namespace {

/// Phase I with the report's illuminant given by id ("" = D50).
SurfaceFitResult fit_surface_under(const MethodChoice& start, const SpectralData& measured, const SpectralData& target,
                                   SurfaceFitOptions options, const std::string& illuminant) {
  if (!illuminant.empty()) options.illuminant = illuminant_spd(illuminant);
  return fit_surface(start, measured, target, options);
}

/// Phase II with the illuminant given by id ("" = D50).
JointFitResult fit_joint_under(const MethodChoice& start, const PatchMatrix& camera_RGB, const SpectralData& reflectances,
                               JointFitOptions options, const std::string& illuminant) {
  if (!illuminant.empty()) options.illuminant = illuminant_spd(illuminant);
  return fit_surface_joint_Abed2013(start, camera_RGB, reflectances, options);
}

/// The corrected 3×3 with its 3×4 as a 3 × 4 row-major array (12 values).
struct Corrected3x3 {
  Eigen::MatrixXd matrix_3x4;
  Mat3 matrix_prime, matrix;
  double mu = 1;
};
Corrected3x3 corrected_3x3(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ, const Vec3& white_RGB,
                           const Vec3& white_XYZ) {
  const CorrectedMatrix c = fit_corrected_3x3_Abed2013(camera_RGB, reference_XYZ, white_RGB, white_XYZ);
  return {c.matrix_3x4, c.matrix_prime, c.matrix, c.mu};
}

/// The simulated Table IV (geometry_table.hpp): every training chart × method, tested on the
/// matte chart, for one camera (cameraNames()), illuminant id and noise σ.
std::vector<GeometryTableCell> surface_table4(const std::string& camera, const std::string& illuminant, double noise_sigma,
                                              double seed) {
  const GeometryExperiment e = geometry_experiment_Abed2013(camera.empty() ? "Nikon_D850" : camera,
                                                            illuminant.empty() ? "D50" : illuminant, noise_sigma,
                                                            seed > 0 ? static_cast<uint64_t>(seed) : 1);
  return geometry_table_Abed2013(e.training, e.test, e.options);
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_surface) {
  { using S = SaundersonGeometry; value_object<S>("SaundersonGeometry") FIELD(k1) FIELD(k2) FIELD(k_ins); }
  { using S = SaundersonPreset; value_object<S>("SaundersonPreset") FIELD(id) FIELD(label) FIELD(role) FIELD(geometry)
      FIELD(source); }
  { using S = SurfaceFitOptions; value_object<S>("SurfaceFitOptions") FIELD(range_min) FIELD(range_max) FIELD(illuminant)
      FIELD(observer) FIELD(per_wavelength) FIELD(free) FIELD(max_evaluations); }
  { using S = JointFitOptions; value_object<S>("JointFitOptions") FIELD(illuminant) FIELD(observer) FIELD(white_RGB)
      FIELD(white_reflectance) FIELD(anchor_white) FIELD(free) FIELD(max_evaluations); }
  { using S = Corrected3x3; value_object<S>("Corrected3x3") FIELD(matrix_3x4) FIELD(matrix_prime) FIELD(matrix) FIELD(mu); }

  def<&saunderson_presets>("listSurfacePresets");
  def<&surface_option_table>("listSurfaceOptions");
  def<&correct_surface>("correctSurface");
  def<&surface_choice_text>("surfaceChoiceText");
  def<&fit_surface_under>("fitSurface");
  def<&fit_joint_under>("fitSurfaceJoint");
  def<&corrected_3x3>("fitCorrected3x3");
  def<&geometry_table_methods>("surfaceTable4Methods");
  def<&surface_table4>("surfaceTable4");
}

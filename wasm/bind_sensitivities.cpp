// Declarations: camera spectral sensitivities for eq (7)'s channel areas A_R, A_G, A_B (Guarnera
// 2018) — a built-in camera's curves, a CSV read by the core's parser, the Jiang 2013 estimate
// from per-patch camera RGB paired by id with reflectances under an illuminant, the comparison of
// two sets (RMS with each channel at peak 1; areas) and the CSV the CLI writes; the estimate's
// own illuminant (wavelength and one value column) and reflectance files (the CLI's --illuminant
// and --reflectances files).
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/sensitivities.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_sensitivities) {
  { using S = SensitivityOptions; value_object<S>("SensitivityOptions") FIELD(components) FIELD(smoothness) FIELD(exclude_cameras); }
  { using S = SensitivityEstimate; value_object<S>("SensitivityEstimate") FIELD(ssf) FIELD(residual) FIELD(residual_rms)
      FIELD(patches) FIELD(components) FIELD(basis_cameras) FIELD(areas) FIELD(clipped) FIELD(ids) FIELD(unpaired)
      FIELD(paired_reflectances) FIELD(paired_RGB); }
  { using S = SensitivityUncertainty; value_object<S>("SensitivityUncertainty") FIELD(ratio) FIELD(u_loo) FIELD(u_K) FIELD(u)
      FIELD(coverage) FIELD(loo_bases) FIELD(components_tried) FIELD(nearest_camera) FIELD(nearest_distance)
      FIELD(residual_limit) FIELD(distance_limit) FIELD(warnings) FIELD(message); }
  { using S = SensitivityUncertaintyOptions; value_object<S>("SensitivityUncertaintyOptions") FIELD(coverage)
      FIELD(residual_limit) FIELD(distance_limit); }

  def<&camera_ssf>("cameraSensitivities");
  def<&read_ssf_csv>("readSensitivitiesCsv");
  def<&illuminant_spd>("illuminantSpectrum");
  def<&read_illuminant_csv>("readIlluminantCsv");
  def<&read_reflectance_file>("readReflectanceFile");
  def<&estimate_sensitivities_by_id>("estimateSensitivities");
  def<&sensitivity_uncertainty>("sensitivityUncertainty");
  def<&sensitivity_rms>("sensitivityRms");
  def<&channel_areas>("channelAreas");
  def<&sensitivities_to_csv>("sensitivitiesToCsv");
}

// Declarations: camera spectral sensitivities for eq (7)'s channel areas A_R, A_G, A_B (Guarnera
// 2018) — a built-in camera's curves, a CSV read by the core's parser, the Jiang 2013 estimate
// from per-patch camera RGB paired by id with reflectances under an illuminant, the comparison of
// two sets (RMS with each channel at peak 1; areas) and the CSV the CLI writes; the estimate's
// own illuminant (wavelength and one value column) and reflectance files (the CLI's --illuminant
// and --reflectances files). The estimate (SensitivityEstimate) and its uncertainty
// (SensitivityUncertainty) cross by their field lists (tristim/absolute/fields.hpp): the object
// `tristim sensitivities estimate` prints and its "uncertainty"; the uncertainty is computed from
// the same inputs as the estimate (ids, RGB, reflectances, illuminant, options), paired alike.
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/sensitivities.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "declare.hpp"
#include "types.hpp"

using namespace tristim;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_sensitivities) {
  STRUCT(SensitivityOptions, components, smoothness, exclude_cameras);
  STRUCT(SensitivityUncertaintyOptions, coverage, residual_limit, distance_limit);

  def<&camera_ssf>("cameraSensitivities");
  def<&read_ssf_csv>("readSensitivitiesCsv");
  def<&illuminant_spd>("illuminantSpectrum");
  def<&read_illuminant_csv>("readIlluminantCsv");
  def<&read_reflectance_file>("readReflectanceFile");
  def<&estimate_sensitivities_by_id>("estimateSensitivities");
  def<&sensitivity_uncertainty_by_id>("sensitivityUncertainty");
  def<&sensitivity_rms>("sensitivityRms");
  def<&channel_areas>("channelAreas");
  def<&sensitivities_to_csv>("sensitivitiesToCsv");
}

// Declarations: camera spectral sensitivities for eq (7)'s channel areas A_R, A_G, A_B (Guarnera
// 2018) — a built-in camera's curves, a CSV read by the core's parser, the Jiang 2013 estimate
// from per-patch camera RGB paired by id with reflectances under an illuminant, the comparison of
// two sets (RMS with each channel at peak 1; areas) and the CSV the CLI writes; the estimate's
// own illuminant (wavelength and one value column) and reflectance files (the CLI's --illuminant
// and --reflectances files). The uncertainty (SensitivityUncertainty) crosses by its field list
// (tristim/absolute/fields.hpp): the object `tristim sensitivities estimate` prints as "uncertainty".
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
  STRUCT(SensitivityEstimate, ssf, residual, residual_rms, patches, components, basis_cameras, areas, clipped, ids,
           unpaired, paired_reflectances, paired_RGB);
  STRUCT(SensitivityUncertaintyOptions, coverage, residual_limit, distance_limit);

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

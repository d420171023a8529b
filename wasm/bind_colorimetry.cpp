// Declarations: reference data (built-in charts, measurement files), pairing by id, the spectral
// locus, colour differences, display colours and the virtual camera.
#include "tristim/chart/reference.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

namespace {

/// A measurement file as reference under an illuminant and observer (chart_id = the file name).
ReferenceChart parse_reference_file(const std::string& text, const std::string& file_name, const std::string& illuminant,
                                    Observer observer) {
  ReferenceChart r = reference_from_table(read_patch_file(text, file_name), illuminant_spd(illuminant), observer);
  r.chart_id = file_name;
  return r;
}

struct SimulatedChart {
  std::vector<std::string> ids;
  std::vector<Vec3> RGB;
};
/// The virtual camera's RGB of a built-in chart's patches (same numbers as `tristim simulate`).
SimulatedChart simulate_camera(const std::string& camera, const std::string& chart, const std::string& illuminant,
                               const SimulationOptions& options) {
  const SpectralData refl = chart_reflectances(chart);
  return {refl.names, simulate_camera_RGB(camera_ssf(camera), refl, illuminant_spd(illuminant), options)};
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_colorimetry) {
  { using S = ReferenceChart; value_object<S>("ReferenceChart") FIELD(chart_id) FIELD(illuminant_id) FIELD(observer)
      FIELD(ids) FIELD(labels) FIELD(XYZ) FIELD(Lab) FIELD(sRGB) FIELD(white); }
  { using S = SpectralData; value_object<S>("SpectralData") FIELD(wavelengths) FIELD(names) FIELD(values) FIELD(linear); }
  { using S = PatchTable; value_object<S>("PatchTable") FIELD(format) FIELD(ids) FIELD(labels) FIELD(has_XYZ) FIELD(has_Lab)
      FIELD(has_RGB) FIELD(has_spectra) FIELD(XYZ) FIELD(Lab) FIELD(RGB) FIELD(spectra) FIELD(keywords); }
  { using S = PatchPairs; value_object<S>("PatchPairs") FIELD(ids) FIELD(measured) FIELD(reference)
      FIELD(missing_in_measured) FIELD(missing_in_reference) FIELD(measured_rows) FIELD(reference_rows); }
  { using S = SpectralLocus; value_object<S>("SpectralLocus") FIELD(wavelengths) FIELD(x) FIELD(y); }
  { using S = SimulationOptions; value_object<S>("SimulationOptions") FIELD(white_level) FIELD(noise_sigma) FIELD(seed)
      FIELD(oecf) FIELD(oecf_gamma) FIELD(oecf_scale) FIELD(clip_max) FIELD(quantise); }
  { using S = SimulatedChart; value_object<S>("SimulatedChart") FIELD(ids) FIELD(RGB); }

  def<&reference_chart>("referenceChart");
  def<&parse_reference_file>("parseReferenceFile");
  def<&read_patch_file>("parsePatchFile");
  def<&normalise_patch_id>("normalisePatchId");
  def<&pair_by_id>("pairById");
  def<&spectral_locus>("spectralLocus");
  def<&delta_E>("deltaE");
  def<&each_row<&XYZ_to_Lab>>("XYZToLab");
  def<&each_row<&display_sRGB>>("XYZToDisplaySRGB");
  def<&display_matrix>("displayMatrix");
  def<&simulate_camera>("simulateCamera");
}

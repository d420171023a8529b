// Declarations: the linearisation stage (issue 11) — the table with what each row needs, a fit of
// one row, its application and inverse, curve samples for plots — and spectral characterisation
// (Shen et al. 2008 eqs 26-28). LinearisationListing, Linearisation, CurveSamples, SpectralModel and
// SpectralEvaluation cross by their field lists (the objects their JSON is: convert_fields.hpp); the
// rest with their C++ field names (boundary.hpp).
#include "tristim/chart/reference.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/linearisation/spectral.hpp"
#include "declare.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using wasm::def;

namespace {

/// Spectral evaluation under a named illuminant ("" = D65, the paper's).
SpectralEvaluation evaluate_spectral_under(const SpectralModel& model, const std::vector<std::string>& ids,
                                           const PatchMatrix& camera_RGB, const SpectralData& measured,
                                           const std::string& illuminant, Observer observer) {
  return evaluate_spectral(model, ids, camera_RGB, measured, illuminant_spd(illuminant.empty() ? "D65" : illuminant), observer);
}

MethodInfo spectral_info() { return spectral_method(); }

std::string linearisation_text(const Linearisation& l) { return linearisation_json(l).dump(2) + "\n"; }
Linearisation linearisation_from_text(const std::string& text) { return linearisation_from_json(json::parse(text)); }
std::string spectral_model_text(const SpectralModel& m) { return spectral_model_json(m).dump(2) + "\n"; }

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_linearisation) {
  STRUCT(LinearisationData, camera_RGB, ids, full_scale, reference_XYZ, white, reflectances, basis_reflectances);

  def<&linearisation_listing>("listLinearisations");
  def<&fit_linearisation>("fitLinearisation");
  def<&linearise>("linearise");
  def<&delinearise>("delinearise");
  def<&sample_curve>("sampleCurve");
  def<&linearisation_text>("linearisationToJson");
  def<&linearisation_from_text>("linearisationFromJson");
  def<&chart_reflectances>("chartReflectances");
  def<&fit_spectral>("fitSpectral");  // options (spectralMethod's) may be left out: the paper's non-grey training
  def<&spectral_info>("spectralMethod");
  def<&estimate_reflectances>("estimateReflectances");
  def<&evaluate_spectral_under>("evaluateSpectral");
  def<&spectral_csv>("spectralCsv");
  def<&spectral_model_text>("spectralModelToJson");
}

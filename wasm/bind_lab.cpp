// Declarations: the colorimetry lab — a chart photograph rendered from measured spectra as DNG
// bytes plus its truth (JSON text), and camera quality (ISO 17321-1 SMI, Vora–Trussell μ, the
// ranking of the 52 cameras, the best-fit CMF combination for the plot), and the exercises.
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/lab/smi.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_lab) {
  { using S = LabRenderOptions; value_object<S>("LabRenderOptions") FIELD(camera) FIELD(sensitivities) FIELD(chart)
      FIELD(illuminant) FIELD(illuminant_spd) FIELD(surface) FIELD(width) FIELD(height) FIELD(corners) FIELD(exposure)
      FIELD(falloff) FIELD(flare) FIELD(shot_gain) FIELD(read_noise) FIELD(seed) FIELD(bits) FIELD(black) FIELD(cfa); }
  { using S = LabRenderFiles; value_object<S>("LabRenderFiles") FIELD(dng) FIELD(truth); }
  { using S = CameraQuality; value_object<S>("CameraQuality") FIELD(camera) FIELD(smi) FIELD(mu_factor) FIELD(mean_dE)
      FIELD(matrix) FIELD(dE); }
  { using S = LutherFit; value_object<S>("LutherFit") FIELD(wavelengths) FIELD(camera) FIELD(fit) FIELD(coefficients); }

  { using S = ColourRow; value_object<S>("ColourRow") FIELD(illuminant) FIELD(observer) FIELD(XYZ) FIELD(Lab) FIELD(x) FIELD(y); }
  { using S = SpectraToColour; value_object<S>("SpectraToColour") FIELD(chart) FIELD(patch) FIELD(wavelengths)
      FIELD(reflectance) FIELD(stimulus) FIELD(illuminants) FIELD(rows); }
  { using S = OverfitOptions; value_object<S>("OverfitOptions") FIELD(models) FIELD(training) FIELD(noise) FIELD(seed); }
  { using S = OverfitRow; value_object<S>("OverfitRow") FIELD(model) FIELD(training) FIELD(terms) FIELD(patches) FIELD(ok)
      FIELD(error_code) FIELD(message) FIELD(train_dE00) FIELD(loo_dE00) FIELD(test_dE00); }

  def<&lab_render_files>("labRender");
  def<&lab_spectra_to_colour>("labSpectraToColour");
  def<&lab_overfit_exercise>("labOverfit");
  def<&cmf_sensitivities>("cmfSensitivities");
  def<&lab_chart_ids>("listLabCharts");
  def<&camera_quality>("cameraQuality");
  def<&camera_quality_ranking>("cameraQualityRanking");
  def<&luther_fit>("lutherFit");
}

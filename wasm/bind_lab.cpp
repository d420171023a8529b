// Declarations: the colorimetry lab — a chart photograph rendered from measured spectra as DNG
// bytes plus its truth (JSON text), and camera quality (ISO 17321-1 SMI, Vora–Trussell μ, the
// ranking of the 52 cameras, the best-fit CMF combination for the plot), the exercises, and the
// metamerism explorer (pairs searched in the Munsell set, metamers constructed).
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/lab/smi.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_lab) {
  { using S = LabRenderOptions; value_object<S>("LabRenderOptions") FIELD(camera) FIELD(sensitivities) FIELD(chart)
      FIELD(illuminant) FIELD(illuminant_spd) FIELD(surface) FIELD(width) FIELD(height) FIELD(corners) FIELD(exposure)
      FIELD(falloff) FIELD(flare) FIELD(shot_gain) FIELD(read_noise) FIELD(seed) FIELD(bits) FIELD(black) FIELD(cfa)
      FIELD(oecf) FIELD(jpeg_quality); }
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

  { using S = MetamerOptions; value_object<S>("MetamerOptions") FIELD(illuminant) FIELD(illuminant_spd) FIELD(second)
      FIELD(second_spd) FIELD(observer) FIELD(camera) FIELD(sensitivities) FIELD(match) FIELD(max_match) FIELD(top); }
  { using S = MetamerView; value_object<S>("MetamerView") FIELD(viewer) FIELD(XYZ_a1) FIELD(XYZ_b1) FIELD(XYZ_a2) FIELD(XYZ_b2)
      FIELD(Lab_a1) FIELD(Lab_b1) FIELD(Lab_a2) FIELD(Lab_b2) FIELD(dE00_1) FIELD(dE00_2); }
  { using S = MetamerPair; value_object<S>("MetamerPair") FIELD(a) FIELD(b) FIELD(reflectance_a) FIELD(reflectance_b)
      FIELD(alpha) FIELD(views); }
  { using S = MetamerResult; value_object<S>("MetamerResult") FIELD(wavelengths) FIELD(illuminant) FIELD(second)
      FIELD(observer) FIELD(camera) FIELD(match) FIELD(camera_matrix) FIELD(max_match) FIELD(compared) FIELD(all_pairs)
      FIELD(matching) FIELD(pairs); }

  def<&lab_render_files>("labRender");
  def<&lab_spectra_to_colour>("labSpectraToColour");
  def<&lab_overfit_exercise>("labOverfit");
  def<&cmf_sensitivities>("cmfSensitivities");
  def<&lab_chart_ids>("listLabCharts");
  def<&lab_oecf_ids>("listLabOecfs");
  def<&camera_quality>("cameraQuality");
  def<&camera_quality_ranking>("cameraQualityRanking");
  def<&luther_fit>("lutherFit");
  def<&metamer_pairs>("labMetamers");
  def<&construct_metamer>("labConstructMetamer");
  def<&munsell_ids>("listMunsell");
}

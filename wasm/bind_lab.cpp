// Declarations: the colorimetry lab — a chart photograph rendered from measured spectra as DNG
// bytes plus its truth (JSON text), and camera quality (ISO 17321-1 SMI, Vora–Trussell μ, the
// ranking of the 52 cameras, the best-fit CMF combination for the plot).
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

  def<&lab_render_files>("labRender");
  def<&lab_chart_ids>("listLabCharts");
  def<&camera_quality>("cameraQuality");
  def<&camera_quality_ranking>("cameraQualityRanking");
  def<&luther_fit>("lutherFit");
}

// Declarations: the colorimetry lab — a chart photograph rendered from measured spectra as DNG
// bytes plus its truth (JSON text), and camera quality (ISO 17321-1 SMI, Vora–Trussell μ, the
// ranking of the 52 cameras, the best-fit CMF combination for the plot), the exercises, and the
// metamerism explorer (pairs searched in the Munsell set, metamers constructed); the lab's number
// options (lab_option_table: the page's boxes).
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/lab/smi.hpp"
#include "declare.hpp"
#include "types.hpp"

using namespace tristim;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_lab) {
  STRUCT(LabRenderOptions, camera, sensitivities, chart, illuminant, illuminant_spd, surface, width, height, corners,
           exposure, falloff, flare, shot_gain, read_noise, seed, bits, black, cfa, oecf, jpeg_quality);
  STRUCT(LabRenderFiles, dng, truth, reference);
  STRUCT(LabFileKind, id, label, extension, media_type, through_oecf);
  STRUCT(LutherFit, wavelengths, camera, fit, coefficients);

  STRUCT(ColourRow, illuminant, observer, XYZ, Lab, x, y);
  STRUCT(SpectraToColour, chart, patch, wavelengths, reflectance, stimulus, illuminants, rows);
  STRUCT(OverfitOptions, models, training, noise, seed);

  STRUCT(MetamerOptions, illuminant, illuminant_spd, second, second_spd, observer, camera, sensitivities, match,
           max_match, top);

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
  def<&lab_option_table>("listLabOptions");
  def<&lab_file_kinds>("listLabFileKinds");
  def<&metamer_match_table>("listMetamerMatches");
  def<&shen_training_table>("listShenTrainings");
  def<&lab_option>("labOption");
}

// Declarations: the colorimetry lab's exercises 3-5 (the papers' tables) and their results tables
// (LabTable: columns with units, cells as text; lab_table_csv is the CSV the page downloads).
#include "tristim/lab/exercises.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_lab_exercises) {
  { using S = ShenOptions; value_object<S>("ShenOptions") FIELD(chart) FIELD(J) FIELD(sigmas) FIELD(J_table) FIELD(sigma_table)
      FIELD(seeds) FIELD(seed); }
  { using S = ShenRow; value_object<S>("ShenRow") FIELD(method) FIELD(J) FIELD(L) FIELD(sigma) FIELD(ok) FIELD(error_code)
      FIELD(r_squared) FIELD(colorimetric_dE00) FIELD(spectral_dE00) FIELD(spectral_rms); }
  { using S = ShenExercise; value_object<S>("ShenExercise") FIELD(chart) FIELD(non_grey) FIELD(j_sweep) FIELD(l_table); }
  { using S = Table4Row; value_object<S>("Table4Row") FIELD(training) FIELD(method) FIELD(patches) FIELD(ok) FIELD(error_code)
      FIELD(dE_xyz_mean) FIELD(dE_xyz_max) FIELD(dE00_mean) FIELD(dE00_max) FIELD(mu) FIELD(paper_dE_xyz_mean)
      FIELD(paper_dE_xyz_max) FIELD(paper_dE00_mean) FIELD(paper_dE00_max); }
  { using S = ExposureRow; value_object<S>("ExposureRow") FIELD(model) FIELD(k) FIELD(dE00_mean) FIELD(dE00_max); }
  { using S = GuarneraRow; value_object<S>("GuarneraRow") FIELD(light) FIELD(training) FIELD(transform) FIELD(shots)
      FIELD(NRMSE) FIELD(dE00_mean) FIELD(relative_Y_error) FIELD(paper_NRMSE); }

  def<&lab_table_csv>("labTableCsv");
  def<&lab_shen_exercise>("labShen");
  def<&shen_j_table>("labShenJTable");
  def<&shen_l_table>("labShenLTable");
  def<&lab_table4_exercise>("labTable4");
  def<&table4_table>("labTable4Table");
  def<&lab_exposure_exercise>("labExposure");
  def<&exposure_table>("labExposureTable");
  def<&lab_guarnera_table4>("labGuarneraTable4");
  def<&guarnera_table>("labGuarneraTable");
}

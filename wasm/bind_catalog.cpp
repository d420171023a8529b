// Declarations: version, built-in data, and every table the page builds its pickers from —
// charts, illuminants, observers, models and their families, the method tables of each stage
// (MethodInfo / OptionSpec rows; the flat-field modes too), chart layouts, the custom grid's and the
// sampling's option rows, the sensitivity estimate's option rows and the Absolute mode's choices of
// sensitivities, a light trap's rows for an image's size, and the corner homography. ModelInfo,
// ModelFamily, OptionSpec and MethodInfo cross by their field lists (convert_fields.hpp: the objects
// `tristim models --json` prints; a bound that is not a number is null); the rest by value_object.
#include "tristim/absolute/options_table.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/data.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#include "tristim/surface/surface.hpp"
#include "tristim/version.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

namespace {
std::string version() { return kVersion; }
std::vector<MethodInfo> objectives() { return method_infos(objective_table()); }
}  // namespace

EMSCRIPTEN_BINDINGS(tristim_catalog) {
  { using S = ChartInfo; value_object<S>("ChartInfo") FIELD(id) FIELD(name) FIELD(patches) FIELD(rows) FIELD(columns) FIELD(source); }
  { using S = IlluminantInfo; value_object<S>("IlluminantInfo") FIELD(id) FIELD(name); }
  { using S = ObserverInfo; value_object<S>("ObserverInfo") FIELD(id) FIELD(name); }
  { using S = SurfaceListing; value_object<S>("SurfaceListing") FIELD(id) FIELD(label) FIELD(reference) FIELD(options)
      FIELD(coefficients) FIELD(equation) FIELD(geometry); }
  { using S = PatchCell; value_object<S>("PatchCell") FIELD(id) FIELD(row) FIELD(column) FIELD(u0) FIELD(v0) FIELD(u1) FIELD(v1); }
  { using S = ChartLayout; value_object<S>("ChartLayout") FIELD(chart) FIELD(rows) FIELD(columns) FIELD(gap) FIELD(patches); }

  def<&version>("version");
  def<&builtin_files>("builtinFiles");
  def<&builtin_file>("builtinFile");
  def<&list_charts>("listCharts");
  def<&list_illuminants>("listIlluminants");
  def<&list_observers>("listObservers");
  def<&camera_names>("cameraNames");
  def<&model_table>("listModels");
  def<&model_families>("listModelFamilies");
  def<&objectives>("listObjectives");
  def<&objective_choice_label>("objectiveChoiceLabel");
  def<&surface_listing>("listSurfaceCorrections");
  def<&flat_field_methods>("listFlatFieldModes");
  def<&complete_choice>("completeChoice");
  def<&parse_choice>("parseChoice");
  def<&chart_layout_ids>("listChartLayouts");
  def<&chart_layout>("chartLayout");
  def<&layout_option_table>("listLayoutOptions");
  def<&sensitivity_option_table>("listSensitivityOptions");
  def<&absolute_sensitivity_table>("listAbsoluteSensitivities");
  def<&light_trap_option_table>("listLightTrapOptions");
  def<&homography_unit_square>("homographyUnitSquare");
}

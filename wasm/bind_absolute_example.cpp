// Declarations: the absolute tele-colorimeter's inputs as a user gives them — the stimuli CSV
// (tristim/absolute/recipe.hpp's rows: per patch, or a region naming a frame of the bracket) — and
// the virtual-camera example (tristim/absolute/example.hpp): its bracket, lens-cap frames and flat
// as RawImage handles (call .delete()), the training stimuli CSV, the test scene (the cells as
// region rows) and the names the frames stand for.
#include "raw_handle.hpp"
#include "tristim/absolute/example.hpp"
#include "tristim/absolute/recipe.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_absolute_example) {
  { using S = ExampleRegion; value_object<S>("ExampleRegion") FIELD(id) FIELD(x) FIELD(y) FIELD(w) FIELD(h) FIELD(XYZ); }
  { using S = AbsoluteExampleOptions; value_object<S>("AbsoluteExampleOptions") FIELD(camera) FIELD(cell)
      FIELD(white_luminance) FIELD(illuminant) FIELD(colour_training) FIELD(seed); }
  { using S = AbsoluteExample; value_object<S>("AbsoluteExample") FIELD(camera) FIELD(bracket) FIELD(labels) FIELD(frames)
      FIELD(lens_cap) FIELD(flat) FIELD(regions) FIELD(white_id) FIELD(frame_names) FIELD(lens_cap_names) FIELD(flat_name)
      FIELD(stimuli_csv) FIELD(test_csv); }

  def<&read_absolute_stimuli>("readAbsoluteStimuli");
  def<&absolute_stimuli_to_csv>("absoluteStimuliToCsv");
  def<&make_absolute_example>("absoluteExample");
  // The example's pickers (the page's catalog: exampleLights, exampleTrainings).
  { using S = ExampleChoice; value_object<S>("ExampleChoice") FIELD(id) FIELD(label) FIELD(about) FIELD(transform); }
  def<&example_light_table>("listExampleLights");
  def<&example_training_table>("listExampleTrainings");
}

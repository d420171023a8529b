// Declarations: the lab's chart of one's own — uploaded reflectances (readReflectanceFile) rendered
// as a generated grid; Munsell selections go through labRender's `chart` ("munsell:…").
#include "tristim/lab/render.hpp"
#include "types.hpp"

using namespace tristim;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_lab_render) {
  def<&lab_render_reflectance_files>("labRenderReflectances");
}

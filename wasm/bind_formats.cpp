// Declarations: the readers of files other tools load (tristim/profile/headers.hpp) — a .cube's
// sizes, title and domain, an ICC profile's header and tags (lcms2) — for a download or anyone's
// file read back in the page. Their results cross by their field lists.
#include "tristim/profile/headers.hpp"
#include "types.hpp"

using namespace tristim;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_formats) {
  def<&read_cube_header>("readCubeHeader");
  def<&read_icc_header>("readIccHeader");
}

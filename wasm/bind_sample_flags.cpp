// Declarations: the sample flags a recipe may leave out (sampling.exclude_flags), one OptionSpec
// row each (tristim/profile/recipe.hpp, sample_flag_table): the fit step's toggles.
#include "tristim/profile/recipe.hpp"
#include "types.hpp"

using namespace tristim;
using wasm::def;

EMSCRIPTEN_BINDINGS(tristim_sample_flags) { def<&sample_flag_table>("listSampleFlags"); }

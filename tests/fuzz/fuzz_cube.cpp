// .cube header reader (profile/headers.hpp): keywords, sizes and the row count of any text.
#include "fuzz_support.hpp"
#include "tristim/profile/headers.hpp"

TRISTIM_FUZZ_TARGET({ tristim::read_cube_header(input, "fuzz.cube"); })

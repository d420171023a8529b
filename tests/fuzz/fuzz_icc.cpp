// ICC header reader (profile/headers.hpp): the header checks, then lcms2's header and tag table and
// the description tag of any bytes.
#include <vector>

#include "fuzz_support.hpp"
#include "tristim/profile/headers.hpp"

TRISTIM_FUZZ_TARGET({ tristim::read_icc_header(std::vector<std::uint8_t>(input.begin(), input.end()), "fuzz.icc"); })

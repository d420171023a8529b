// Project files (.tristim, share/link.hpp): the container reader (header length, header JSON, image
// offsets and SHA-256s, the payload inside); what it accepts is written again and must read back
// to the same bytes. Seeds: corpus/share_project/.
#include "fuzz_support.hpp"
#include "tristim/share/link.hpp"

TRISTIM_FUZZ_TARGET({
  tristim::fuzz::round_trip(
      input, [](const std::string& b) { return tristim::project_from_bytes(b); },
      [](const tristim::Project& p) { return tristim::project_to_bytes(p); });
})

// Project files (.tristim, share/link.hpp): the container reader (header length, header JSON, image
// offsets and SHA-256s, the payload inside); what it accepts is written again and must read back
// to the same bytes. Seeds: corpus/share_project/.
#include <cstdlib>

#include "fuzz_support.hpp"
#include "tristim/share/link.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::Project read = tristim::project_from_bytes(input);
  const std::string bytes = tristim::project_to_bytes(read);
  std::string again;
  try {
    again = tristim::project_to_bytes(tristim::project_from_bytes(bytes));
  } catch (const tristim::Error&) {
    std::abort();
  }
  if (again != bytes) std::abort();
})

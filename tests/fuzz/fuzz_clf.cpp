// Common LUT Format (profile/clf.hpp): the strict reader; for a file it accepts, its JSON summary
// (which applies it to camera 1, 1, 1) and a write/read round trip of what the writer writes.
#include "fuzz_support.hpp"
#include "tristim/profile/clf.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::ClfDocument c = tristim::read_clf(input);
  tristim::clf_json(c);
  tristim::apply_clf(c, tristim::Vec3(0.2, 0.5, 1.5));
  tristim::read_clf(tristim::write_clf(c));
})

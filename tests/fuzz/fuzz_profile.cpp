// Profile JSON (profile/profile.hpp) and, for a profile it accepts, the exports (ICC v4/v2, .cube).
#include "fuzz_support.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/profile.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::Profile p = tristim::profile_from_json(input);
  tristim::profile_to_json(p);
  tristim::IccOptions o;
  o.grid_points = 5;  // small: the sampler is what is under test, not the grid size
  tristim::export_icc(p, o);
  o.version = 2.4;
  tristim::export_icc(p, o);
  tristim::export_cube(p, 3);
})

// DNG camera profiles (profile/dcp.hpp): the strict reader; for a file it accepts, its JSON summary
// (which runs the reference pipeline at each illuminant's neutral), one rendering through the
// pipeline and the HueSatMap, and a write/read round trip of what the writer writes.
#include "fuzz_support.hpp"
#include "tristim/profile/dcp.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::Dcp d = tristim::read_dcp(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  tristim::dcp_json(d);
  const tristim::DcpTransform t = tristim::dcp_camera_to_xyz(d, tristim::Vec3(0.5, 1.0, 0.7), 0);
  tristim::dcp_render(d, t, tristim::Vec3(0.2, 0.3, 0.1));
  if (d.look_table.empty() && !d.has_baseline_exposure_offset && !d.has_default_black_render)
    tristim::read_dcp(tristim::write_dcp(d));
})

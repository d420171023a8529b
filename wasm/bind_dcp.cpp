// Declarations: DNG camera profiles (profile/dcp.hpp) for the page's Export step: a single-
// illuminant DCP of one profile (the CLI's `tristim export --profile p.json --dcp x.dcp`), a dual-
// illuminant one of two (`--second p2.json`), and the
// engine's strict reader, whose result crosses as the JSON `tristim inspect x.dcp` prints.
#include "tristim/profile/dcp.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using emscripten::value_object;
using wasm::def;

template <>  // the object dcp_json is (every tag, plus the white checks)
struct tristim::wasm::Conv<Dcp> : wasm::JsonOutput<Dcp, &dcp_json> {};

namespace {

/// The page writes one profile (single-illuminant); make_dcp's optional second profile is a
/// pointer, which embind does not take, hence this name for the one-profile call.
std::vector<std::uint8_t> export_dcp(const Profile& profile, const DcpOptions& options) {
  return write_dcp(make_dcp(profile, options));
}
/// The dual-illuminant DCP of two profiles of the same camera (`tristim export --second`).
std::vector<std::uint8_t> export_dcp_dual(const Profile& profile, const Profile& second, const DcpOptions& options) {
  return write_dcp(make_dcp(profile, options, &second));
}

}  // namespace

EMSCRIPTEN_BINDINGS(tristim_dcp) {
  { using S = DcpOptions; value_object<S>("DcpOptions") FIELD(camera_model) FIELD(profile_name) FIELD(copyright)
      FIELD(embed_policy) FIELD(illuminant) FIELD(second_illuminant) FIELD(hue_sat_map) FIELD(rgb_scale)
      FIELD(linear_tone_curve); }

  def<&export_dcp>("exportDcp");
  def<&export_dcp_dual>("exportDcpDual");
  def<static_cast<Dcp (*)(const std::vector<std::uint8_t>&)>(&read_dcp)>("readDcp");
}

// Share links (share/link.hpp): the reader of a whole link or payload text (first byte 'L'), and the
// reader of a link's content behind a valid compression and check (first byte 'C', so the fuzzer
// reaches the JSON, the merge patch and the patch values instead of stopping at the check). What
// the reader accepts, the writer writes again and the reader reads to the same payload (a
// round-trip failure is a finding, not a refusal). Seeds: corpus/share_payload/.
#include <cstdlib>

#include "fuzz_support.hpp"
#include "tristim/share/link.hpp"
#include "tristim/share/sha256.hpp"

namespace {
std::string wrap(const std::string& content) {
  tristim::Sha256 h;
  h.update(content);
  const auto sum = h.digest();
  return "1." + tristim::base64url_encode(tristim::deflate_raw(content)) + "." +
         tristim::base64url_encode(std::string(reinterpret_cast<const char*>(sum.data()), 12));
}
}  // namespace

TRISTIM_FUZZ_TARGET({
  if (input.empty()) return 0;
  const std::string rest = input.substr(1);
  const tristim::SharePayload read = tristim::decode_share_payload(input[0] == 'C' ? wrap(rest) : rest);
  const std::string json = tristim::share_payload_json(read).dump();
  std::string again;
  try {
    again = tristim::share_payload_json(tristim::decode_share_payload(tristim::encode_share_payload(read))).dump();
  } catch (const tristim::Error&) {
    std::abort();  // what the writer wrote, the reader must read
  }
  if (again != json) std::abort();
})

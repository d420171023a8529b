// Share links (share/link.hpp): the reader of a whole link or payload text (first byte 'L'), and the
// reader of a link's content behind a valid compression and check — version 1 content (first byte
// 'C') and version 2 content (first byte 'D': JSON, NUL, the binary part) — so the fuzzer reaches
// the JSON, the merge patch, the results' numbers and the patch values instead of stopping at the
// check. What the reader accepts, the writer writes again (version 2, and version 1) and the reader
// reads to the same payload (a round-trip failure is a finding, not a refusal).
// Seeds: corpus/share_payload/ (v1-*: version 1, v2-*: version 2).
#include <cstdlib>

#include "fuzz_support.hpp"
#include "tristim/share/link.hpp"
#include "tristim/share/sha256.hpp"

namespace {
/// A link of `content`: version 1 checks the content, version 2 the compressed bytes.
std::string wrap(const std::string& content, bool v2) {
  const std::string data = tristim::deflate_raw(content, v2 ? std::string_view(tristim::share_link_dictionary()) : std::string_view());
  tristim::Sha256 h;
  h.update(v2 ? data : content);
  const auto sum = h.digest();
  return (v2 ? "2." : "1.") + tristim::base64url_encode(data) + "." +
         tristim::base64url_encode(std::string(reinterpret_cast<const char*>(sum.data()), 12));
}
}  // namespace

TRISTIM_FUZZ_TARGET({
  if (input.empty()) return 0;
  const std::string rest = input.substr(1);
  const tristim::SharePayload read =
      tristim::decode_share_payload(input[0] == 'C' || input[0] == 'D' ? wrap(rest, input[0] == 'D') : rest);
  const std::string json = tristim::share_payload_json(read).dump();
  std::string again, again_v1;
  try {
    again = tristim::share_payload_json(tristim::decode_share_payload(tristim::encode_share_payload(read))).dump();
    again_v1 = tristim::share_payload_json(tristim::decode_share_payload(tristim::encode_share_payload_v1(read))).dump();
  } catch (const tristim::Error&) {
    std::abort();  // what the writer wrote, the reader must read
  }
  if (again != json || again_v1 != json) std::abort();
})

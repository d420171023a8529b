// Writing one little-endian TIFF IFD (TIFF 6.0 §2), shared by the DNG writer (lab/dng_writer.cpp)
// and the DCP writer (profile/export_dcp_tiff.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tristim/error.hpp"

namespace tristim::tiff {

/// One IFD entry: its tag, field type, count of values and the values' bytes (little-endian).
struct Field {
  std::uint16_t tag, type;
  std::uint32_t count;
  std::vector<std::uint8_t> bytes;
};

/// The low 16 bits of v, little-endian.
inline void put16(std::vector<std::uint8_t>& b, std::uint32_t v) {
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}
inline void put32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  put16(b, v & 0xffff);
  put16(b, v >> 16);
}

/// Appends the IFD of `fields` (in the order given) at out.size(), its next-IFD offset 0, then
/// every value longer than 4 bytes, each at an even offset (values begin on a word boundary).
/// `pad_end`: one zero byte after an odd-length last value too, so what follows starts even.
/// Returns where each field's value-or-offset word is in `out` (for patching offsets later).
/// `what` names the file in the error for more than 4 GB.
inline std::vector<std::size_t> append_ifd(std::vector<std::uint8_t>& out, const std::vector<Field>& fields,
                                           bool pad_end, const std::string& what) {
  const std::size_t ifd_end = out.size() + 2 + 12 * fields.size() + 4;
  std::vector<std::uint8_t> data;
  std::vector<std::size_t> value_at;
  put16(out, static_cast<std::uint32_t>(fields.size()));
  for (const Field& f : fields) {
    put16(out, f.tag);
    put16(out, f.type);
    put32(out, f.count);
    value_at.push_back(out.size());
    if (f.bytes.size() <= 4) {
      std::vector<std::uint8_t> v = f.bytes;
      v.resize(4, 0);
      out.insert(out.end(), v.begin(), v.end());
    } else {
      if (data.size() % 2) data.push_back(0);
      const std::size_t at = ifd_end + data.size();
      if (at + f.bytes.size() > std::numeric_limits<std::uint32_t>::max())
        throw Error(ErrorCode::ExportFailed, what + " larger than 4 GB");
      put32(out, static_cast<std::uint32_t>(at));
      data.insert(data.end(), f.bytes.begin(), f.bytes.end());
    }
  }
  if (pad_end && data.size() % 2) data.push_back(0);
  put32(out, 0);  // no next IFD
  out.insert(out.end(), data.begin(), data.end());
  return value_at;
}

}  // namespace tristim::tiff

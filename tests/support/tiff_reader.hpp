// A minimal reader of the first directory of a little-endian classic TIFF, written from the TIFF 6.0
// specification for the tests of the float TIFF exports: independent of libtiff, which writes them.
#pragma once
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace tristim::test {

struct TiffEntry {
  std::uint16_t type = 0;
  std::vector<std::uint32_t> values;  ///< SHORT and LONG values (type 3, 4)
  std::string ascii;                  ///< type 2, without the trailing NUL
};

/// Tag id → entry of the first IFD; fails the test if the bytes are not a little-endian TIFF or
/// an entry points outside the file.
inline std::map<std::uint16_t, TiffEntry> tiff_tags(const std::vector<std::uint8_t>& b) {
  auto u16 = [&](std::size_t at) {
    REQUIRE(at + 2 <= b.size());
    return static_cast<std::uint32_t>(b[at] | b[at + 1] << 8);
  };
  auto u32 = [&](std::size_t at) { return u16(at) | u16(at + 2) << 16; };
  REQUIRE(b.size() >= 8);
  REQUIRE((b[0] == 'I' && b[1] == 'I' && u16(2) == 42));
  const std::size_t ifd = u32(4);
  std::map<std::uint16_t, TiffEntry> tags;
  for (std::uint32_t i = 0, n = u16(ifd); i < n; ++i) {
    const std::size_t e = ifd + 2 + 12 * i;
    TiffEntry t;
    t.type = static_cast<std::uint16_t>(u16(e + 2));
    const std::uint32_t count = u32(e + 4);
    const std::size_t size = t.type == 3 ? 2 : t.type == 4 ? 4 : 1;
    const std::size_t at = count * size <= 4 ? e + 8 : u32(e + 8);
    REQUIRE(at + count * size <= b.size());
    if (t.type == 2) t.ascii.assign(reinterpret_cast<const char*>(b.data() + at), count > 0 ? count - 1 : 0);
    for (std::uint32_t k = 0; (t.type == 3 || t.type == 4) && k < count; ++k)
      t.values.push_back(t.type == 3 ? u16(at + 2 * k) : u32(at + 4 * k));
    tags[static_cast<std::uint16_t>(u16(e))] = t;
  }
  return tags;
}

/// The float samples of a one-strip, uncompressed TIFF, as stored (after checking both).
inline std::vector<float> tiff_float_strip(const std::vector<std::uint8_t>& b) {
  auto tags = tiff_tags(b);
  REQUIRE(tags[259].values == std::vector<std::uint32_t>{1});  // Compression: none
  REQUIRE(tags[273].values.size() == 1);                      // one strip
  REQUIRE(tags[279].values.size() == 1);
  const std::size_t at = tags[273].values[0], n = tags[279].values[0];
  REQUIRE((n % 4 == 0 && at + n <= b.size()));
  std::vector<float> px(n / 4);
  std::memcpy(px.data(), b.data() + at, n);
  return px;
}

}  // namespace tristim::test

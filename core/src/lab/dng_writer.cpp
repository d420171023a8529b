// Minimal DNG writer: one IFD, one uncompressed 16-bit CFA strip, little-endian TIFF.
#include "tristim/lab/dng_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "tristim/error.hpp"
#include "../tiff_ifd.hpp"

namespace tristim {

namespace {

using Entry = tiff::Field;
using tiff::put16;
using tiff::put32;

void set32(std::vector<std::uint8_t>& b, size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

enum : std::uint16_t { BYTE = 1, ASCII = 2, SHORT = 3, LONG = 4, RATIONAL = 5, SRATIONAL = 10 };

Entry shorts(std::uint16_t tag, std::vector<std::uint16_t> v) {
  Entry e{tag, SHORT, static_cast<std::uint32_t>(v.size()), {}};
  for (auto x : v) put16(e.bytes, x);
  return e;
}
Entry longs(std::uint16_t tag, std::vector<std::uint32_t> v) {
  Entry e{tag, LONG, static_cast<std::uint32_t>(v.size()), {}};
  for (auto x : v) put32(e.bytes, x);
  return e;
}
Entry bytes(std::uint16_t tag, std::vector<std::uint8_t> v) {
  return Entry{tag, BYTE, static_cast<std::uint32_t>(v.size()), v};
}
Entry ascii(std::uint16_t tag, const std::string& s) {
  Entry e{tag, ASCII, static_cast<std::uint32_t>(s.size() + 1), {}};
  e.bytes.assign(s.begin(), s.end());
  e.bytes.push_back(0);
  return e;
}
Entry rationals(std::uint16_t tag, const double* v, size_t n, bool is_signed) {
  Entry e{tag, is_signed ? SRATIONAL : RATIONAL, static_cast<std::uint32_t>(n), {}};
  for (size_t i = 0; i < n; ++i) {
    const std::int32_t num = static_cast<std::int32_t>(std::lround(v[i] * 10000.0));
    put32(e.bytes, static_cast<std::uint32_t>(num));
    put32(e.bytes, 10000u);
  }
  return e;
}

// An unsigned rational close to v: 1/n for exposure times such as 1/250 s, else v·10⁶/10⁶.
Entry exact_rational(std::uint16_t tag, double v) {
  Entry e{tag, RATIONAL, 1, {}};
  const double inv = 1.0 / v;
  if (v < 1 && std::fabs(inv - std::round(inv)) < 1e-6 * inv) {
    put32(e.bytes, 1u);
    put32(e.bytes, static_cast<std::uint32_t>(std::lround(inv)));
  } else {
    put32(e.bytes, static_cast<std::uint32_t>(std::lround(v * 1e6)));
    put32(e.bytes, 1000000u);
  }
  return e;
}

// Header, one IFD and its out-of-line payloads; the positions of the StripOffsets (273) and
// ExifIFD (34665) values are returned for patching.
void assemble(const std::vector<Entry>& e, std::vector<std::uint8_t>& out, size_t* strip_field, size_t* exif_field) {
  for (int b : {0x49, 0x49, 42, 0}) out.push_back(static_cast<std::uint8_t>(b));
  put32(out, 8);
  const std::vector<size_t> value_at = tiff::append_ifd(out, e, true, "DNG");
  for (size_t i = 0; i < e.size(); ++i) {
    if (e[i].tag == 273) *strip_field = value_at[i];
    if (e[i].tag == 34665) *exif_field = value_at[i];
  }
}

// 16-bit samples after the header, little-endian, at a 16-byte boundary; patches StripOffsets.
void append_strip(std::vector<std::uint8_t>& out, size_t strip_field, const std::vector<std::uint16_t>& values) {
  while (out.size() % 16) out.push_back(0);
  set32(out, strip_field, static_cast<std::uint32_t>(out.size()));
  const size_t base = out.size();
  out.resize(base + values.size() * 2);
  for (size_t i = 0; i < values.size(); ++i) {
    out[base + 2 * i] = static_cast<std::uint8_t>(values[i]);
    out[base + 2 * i + 1] = static_cast<std::uint8_t>(values[i] >> 8);
  }
}

}  // namespace

std::vector<std::uint8_t> write_dng(const std::vector<std::uint16_t>& values, int width, int height,
                                    const DngWriteOptions& o) {
  if (width < 2 || height < 2 || static_cast<size_t>(width) * height != values.size())
    throw Error(ErrorCode::InvalidArgument, "write_dng: width*height must equal the number of values");
  const int cfa_dim = o.cfa.size() == 4 ? 2 : o.cfa.size() == 36 ? 6 : 0;
  if (cfa_dim == 0)
    throw Error(ErrorCode::InvalidArgument, "write_dng: CFA must have 4 (2x2) or 36 (6x6) letters");
  // CFAPlaneColor lists the colours used (DNG codes: 0 R, 1 G, 2 B, 3 C, 4 M, 5 Y); CFAPattern
  // indexes that list.
  const std::string codes = "RGBCMY";
  std::vector<std::uint8_t> planes, cfa;
  for (char c : codes)
    if (o.cfa.find(c) != std::string::npos) planes.push_back(static_cast<std::uint8_t>(codes.find(c)));
  for (char c : o.cfa) {
    const auto k = codes.find(c);
    if (k == std::string::npos)
      throw Error(ErrorCode::InvalidArgument, "write_dng: CFA letters must be R, G, B, C, M or Y");
    cfa.push_back(static_cast<std::uint8_t>(
        std::find(planes.begin(), planes.end(), static_cast<std::uint8_t>(k)) - planes.begin()));
  }
  const std::uint32_t hw = o.header_width ? o.header_width : static_cast<std::uint32_t>(width);
  const std::uint32_t hh = o.header_height ? o.header_height : static_cast<std::uint32_t>(height);
  const std::uint64_t strip_bytes64 = static_cast<std::uint64_t>(hw) * hh * 2;
  const std::uint32_t strip_bytes =
      strip_bytes64 > 0xffffffffull ? 0xffffffffu : static_cast<std::uint32_t>(strip_bytes64);

  std::vector<Entry> e;
  e.push_back(longs(254, {0}));
  e.push_back(longs(256, {hw}));
  e.push_back(longs(257, {hh}));
  e.push_back(shorts(258, {16}));
  e.push_back(shorts(259, {1}));
  e.push_back(shorts(262, {32803}));
  e.push_back(ascii(271, o.make));
  e.push_back(ascii(272, o.model));
  e.push_back(longs(273, {0}));  // StripOffsets: patched below
  e.push_back(shorts(274, {1}));
  e.push_back(shorts(277, {1}));
  e.push_back(longs(278, {hh}));
  e.push_back(longs(279, {strip_bytes}));
  e.push_back(shorts(284, {1}));
  e.push_back(shorts(33421, {static_cast<std::uint16_t>(cfa_dim), static_cast<std::uint16_t>(cfa_dim)}));
  e.push_back(bytes(33422, cfa));
  if (o.exposure_s > 0) e.push_back(exact_rational(33434, o.exposure_s));
  if (o.f_number > 0) e.push_back(exact_rational(33437, o.f_number));
  if (o.iso > 0) e.push_back(longs(34665, {0}));  // ExifIFD: its offset patched below
  e.push_back(bytes(50706, {1, 4, 0, 0}));
  e.push_back(bytes(50707, {1, 1, 0, 0}));
  e.push_back(ascii(50708, o.make + " " + o.model));
  e.push_back(bytes(50710, planes));  // CFAPlaneColor
  e.push_back(shorts(50711, {1}));    // CFALayout: rectangular
  e.push_back(shorts(50714, {o.black}));
  e.push_back(longs(50717, {o.white}));
  e.push_back(rationals(50721, o.color_matrix.data(), 9, true));
  e.push_back(rationals(50728, o.as_shot_neutral.data(), 3, false));
  e.push_back(shorts(50778, {21}));

  std::vector<std::uint8_t> out;
  out.reserve(values.size() * 2 + 4096);
  size_t strip_offset_field = 0, exif_offset_field = 0;
  assemble(e, out, &strip_offset_field, &exif_offset_field);
  if (o.iso > 0) {  // the EXIF IFD: one entry, ISOSpeedRatings
    set32(out, exif_offset_field, static_cast<std::uint32_t>(out.size()));
    put16(out, 1);
    put16(out, 34855);
    put16(out, SHORT);
    put32(out, 1);
    put16(out, o.iso);
    put16(out, 0);
    put32(out, 0);
  }
  append_strip(out, strip_offset_field, values);
  return out;
}

std::vector<std::uint8_t> write_tiff_rgb16(const std::vector<std::uint16_t>& rgb, int width, int height) {
  if (width < 1 || height < 1 || static_cast<size_t>(width) * height * 3 != rgb.size())
    throw Error(ErrorCode::InvalidArgument, "write_tiff_rgb16: width*height*3 must equal the number of values");
  const std::uint32_t w = static_cast<std::uint32_t>(width), h = static_cast<std::uint32_t>(height);
  std::vector<Entry> e{longs(256, {w}), longs(257, {h}), shorts(258, {16, 16, 16}), shorts(259, {1}), shorts(262, {2}),
                       longs(273, {0}), shorts(274, {1}), shorts(277, {3}), longs(278, {h}),
                       longs(279, {static_cast<std::uint32_t>(rgb.size() * 2)}), shorts(284, {1})};
  std::vector<std::uint8_t> out;
  size_t strip = 0, unused = 0;
  assemble(e, out, &strip, &unused);
  append_strip(out, strip, rgb);
  return out;
}

}  // namespace tristim

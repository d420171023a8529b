// Readers of .cube and ICC headers (rules in tristim/profile/headers.hpp).
#include "tristim/profile/headers.hpp"

#include <cmath>
#include <cstdlib>
#include <new>

#define CMS_NO_REGISTER_KEYWORD 1
#include <lcms2.h>

#include "tristim/error.hpp"

namespace tristim {

namespace fields {
TRISTIM_FIELDS_DEFINE(CubeHeader, member<&CubeHeader::title>("title"), member<&CubeHeader::size>("size"),
                      member<&CubeHeader::shaper_size>("shaper_size"), member<&CubeHeader::entries>("entries"),
                      member<&CubeHeader::domain_min>("domain_min"), member<&CubeHeader::domain_max>("domain_max"));
TRISTIM_FIELDS_DEFINE(IccHeader, member<&IccHeader::size>("size"), member<&IccHeader::version>("version"),
                      member<&IccHeader::device_class>("device_class"),
                      member<&IccHeader::colour_space>("colour_space"), member<&IccHeader::pcs>("pcs"),
                      member<&IccHeader::tags>("tags"), member<&IccHeader::description>("description"));
}  // namespace fields

namespace {

constexpr int kCubeMaxSize = 256, kCubeMaxShaper = 65536;

/// Whitespace-separated words of a line.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

/// A finite number spelled by the whole word, or false.
bool number_of(std::string_view w, double& out) {
  const std::string s(w);
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size() && std::isfinite(out);
}

}  // namespace

CubeHeader read_cube_header(std::string_view text, const std::string& source) {
  CubeHeader h;
  std::int64_t rows = 0;
  bool has_size = false;
  size_t line_no = 0, pos = 0;
  auto fail = [&](const std::string& what) -> void {
    throw Error(ErrorCode::ParseError, source + ": line " + std::to_string(line_no) + ": " + what);
  };
  auto numbers = [&](const std::vector<std::string_view>& w, size_t from, size_t n) {
    std::vector<double> v;
    for (size_t k = from; k < w.size(); ++k) {
      double x = 0;
      if (!number_of(w[k], x)) fail("'" + std::string(w[k]) + "' is not a finite number");
      v.push_back(x);
    }
    if (v.size() != n) fail("expected " + std::to_string(n) + " numbers after " + std::string(w[0]));
    return v;
  };
  auto count = [&](const std::vector<std::string_view>& w, int lo, int hi) {
    const double v = numbers(w, 1, 1)[0];
    if (v != std::floor(v) || v < lo || v > hi)
      fail(std::string(w[0]) + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return static_cast<int>(v);
  };
  while (pos <= text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const auto w = words(line);
    if (w.empty() || w[0][0] == '#') continue;
    const std::string_view key = w[0];
    const char c = key[0];
    if (key == "TITLE") {
      std::string t(line.substr(line.find("TITLE") + 5));
      const size_t a = t.find_first_not_of(" \t"), b = t.find_last_not_of(" \t");
      t = a == std::string::npos ? "" : t.substr(a, b - a + 1);
      if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
      h.title = t;
    } else if (key == "LUT_3D_SIZE") {
      h.size = count(w, 2, kCubeMaxSize);
      has_size = true;
    } else if (key == "LUT_1D_SIZE") {
      h.shaper_size = count(w, 2, kCubeMaxShaper);
    } else if (key == "DOMAIN_MIN" || key == "DOMAIN_MAX") {
      const auto v = numbers(w, 1, 3);
      (key == "DOMAIN_MIN" ? h.domain_min : h.domain_max) = {v[0], v[1], v[2]};
    } else if (key == "LUT_3D_INPUT_RANGE") {
      const auto v = numbers(w, 1, 2);
      h.domain_min = {v[0], v[0], v[0]};
      h.domain_max = {v[1], v[1], v[1]};
    } else if (c == '-' || c == '+' || c == '.' || (c >= '0' && c <= '9')) {
      if (w.size() != 3) fail("expected three numbers, got " + std::to_string(w.size()) + " words");
      numbers(w, 0, 3);
      ++rows;
    }  // other keywords (LUT_1D_INPUT_RANGE, vendor ones) are passed over
  }
  line_no = 0;  // the checks below are about the whole file
  auto whole = [&](const std::string& what) { throw Error(ErrorCode::ParseError, source + ": " + what); };
  if (!has_size) whole("no LUT_3D_SIZE line");
  const std::int64_t cube = std::int64_t(h.size) * h.size * h.size;
  if (rows != h.shaper_size + cube)
    whole(std::to_string(rows) + " table rows, expected " +
          (h.shaper_size ? std::to_string(h.shaper_size) + " shaper + " : std::string()) + std::to_string(h.size) +
          "³ = " + std::to_string(h.shaper_size + cube));
  for (int k = 0; k < 3; ++k)
    if (!(h.domain_min[k] < h.domain_max[k])) whole("DOMAIN_MIN must be below DOMAIN_MAX in each channel");
  h.entries = cube;
  return h;
}

namespace {

std::string signature_text(std::uint32_t s) {
  std::string t;
  for (int shift = 24; shift >= 0; shift -= 8) t += static_cast<char>((s >> shift) & 0xFF);
  const size_t b = t.find_last_not_of(' ');
  return b == std::string::npos ? "" : t.substr(0, b + 1);
}
std::uint32_t big_endian(const std::vector<std::uint8_t>& b, size_t at) {
  return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 | std::uint32_t(b[at + 2]) << 8 | b[at + 3];
}

}  // namespace

IccHeader read_icc_header(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  auto fail = [&](const std::string& what) -> void { throw Error(ErrorCode::ParseError, source + ": " + what); };
  if (bytes.size() < 132) fail(std::to_string(bytes.size()) + " bytes: too short for an ICC profile (128-byte header + tag count)");
  if (signature_text(big_endian(bytes, 36)) != "acsp") fail("no ICC signature \"acsp\" at byte 36");
  const std::uint32_t stated = big_endian(bytes, 0);
  if (stated != bytes.size())
    fail("the header says " + std::to_string(stated) + " bytes, the file has " + std::to_string(bytes.size()));
  struct Open {  // lcms2's context and profile, closed on every path
    cmsContext ctx = cmsCreateContext(nullptr, nullptr);
    cmsHPROFILE profile = nullptr;
    ~Open() {
      if (profile) cmsCloseProfile(profile);
      if (ctx) cmsDeleteContext(ctx);
    }
  } open;
  if (!open.ctx) throw std::bad_alloc();
  open.profile = cmsOpenProfileFromMemTHR(open.ctx, bytes.data(), static_cast<cmsUInt32Number>(bytes.size()));
  if (!open.profile) fail("lcms2 cannot read the header or tag table");
  cmsHPROFILE p = open.profile;
  IccHeader h;
  h.size = stated;
  const cmsUInt32Number v = cmsGetEncodedICCversion(p);
  h.version = std::to_string(v >> 24) + "." + std::to_string((v >> 20) & 0xF);
  h.device_class = signature_text(cmsGetDeviceClass(p));
  h.colour_space = signature_text(cmsGetColorSpace(p));
  h.pcs = signature_text(cmsGetPCS(p));
  const cmsInt32Number n = cmsGetTagCount(p);
  if (n < 0) fail("lcms2 cannot read the tag table");
  for (cmsInt32Number k = 0; k < n; ++k) h.tags.push_back(signature_text(cmsGetTagSignature(p, static_cast<cmsUInt32Number>(k))));
  char text[512] = {0};
  if (cmsIsTag(p, cmsSigProfileDescriptionTag) &&
      cmsGetProfileInfoASCII(p, cmsInfoDescription, "en", "US", text, sizeof text) > 0)
    h.description = text;
  return h;
}

}  // namespace tristim

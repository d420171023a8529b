// DNG Camera Profiles (profile/dcp.hpp): the rules a DCP keeps, and the TIFF-structure writer and
// strict reader of chapter 7 of the DNG Specification 1.6.0.0 ("IIRC" / "MMCR" magic, one IFD).
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "export_dcp_internal.hpp"
#include "../tiff_ifd.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/version.hpp"

namespace tristim {

using namespace dcp_internal;

namespace {

// TIFF field types (TIFF 6.0 §2).
enum : std::uint16_t { kByte = 1, kAscii = 2, kShort = 3, kLong = 4, kRational = 5, kSRational = 10, kFloat = 11 };

std::size_t type_size(std::uint16_t type) {
  switch (type) {
    case 1: case 2: case 6: case 7: return 1;
    case 3: case 8: return 2;
    case 4: case 9: case 11: case 13: return 4;
    case 5: case 10: case 12: return 8;
    default: return 0;
  }
}

}  // namespace

// ---------------------------------------------------------------------------- validation

namespace {

void check_table(const DcpHsvTable& t, const std::string& what, bool dual_data) {
  if (t.empty()) {
    if (!t.data1.empty() || !t.data2.empty())
      throw Error(ErrorCode::ProfileInvalid, what + " data without its dims");
    return;
  }
  check_dims(t.hue, t.sat, t.val, what, true);
  const std::size_t n = static_cast<std::size_t>(t.hue) * t.sat * t.val * 3;
  if (t.data1.empty()) throw Error(ErrorCode::ProfileInvalid, what + " dims without data (DNG 1.6: the data tag is required with the dims)");
  if (t.data1.size() != n || (!t.data2.empty() && t.data2.size() != n))
    throw Error(ErrorCode::ProfileInvalid, what + " data of " + std::to_string(t.data1.size()) + " floats where the dims need " +
                                               std::to_string(n));
  if (!t.data2.empty() && !dual_data)
    throw Error(ErrorCode::ProfileInvalid, what + " has a second table but the profile has no second illuminant");
  if (t.encoding > 1) throw Error(ErrorCode::ProfileInvalid, what + " encoding " + std::to_string(t.encoding) + " (0 linear, 1 sRGB)");
  for (const auto* data : {&t.data1, &t.data2})
    for (std::size_t i = 0; i < data->size(); ++i) {
      const float v = (*data)[i];
      if (!std::isfinite(v) || (i % 3 != 0 && v < 0))
        throw Error(ErrorCode::ProfileInvalid, what + ": entry " + std::to_string(i / 3) + " is not finite or has a negative scale");
    }
}

void check_matrix(const Mat3& m, const std::string& what) {
  if (!m.allFinite()) throw Error(ErrorCode::ProfileInvalid, what + " is not finite");
  if (!(std::abs(m.determinant()) > 1e-12)) throw Error(ErrorCode::ProfileInvalid, what + " is singular");
}

void check_text(const std::string& s, const std::string& what) {
  if (s.find('\0') != std::string::npos) throw Error(ErrorCode::ProfileInvalid, what + " contains a NUL byte");
}

}  // namespace

void dcp_internal::validate(const Dcp& d) {
  check_text(d.unique_camera_model, "UniqueCameraModel");
  check_text(d.profile_name, "ProfileName");
  check_text(d.copyright, "ProfileCopyright");
  check_text(d.calibration_signature, "ProfileCalibrationSignature");
  if (d.illuminant1 < 0 || d.illuminant1 > 65535 || d.illuminant2 < 0 || d.illuminant2 > 65535)
    throw Error(ErrorCode::ProfileInvalid, "a CalibrationIlluminant beyond a SHORT");
  check_matrix(d.color_matrix1, "ColorMatrix1");
  if (d.has_forward_matrix1) check_matrix(d.forward_matrix1, "ForwardMatrix1");
  if (d.has_color_matrix2) {
    if (d.illuminant2 == 0)
      throw Error(ErrorCode::ProfileInvalid, "ColorMatrix2 without CalibrationIlluminant2");
    check_matrix(d.color_matrix2, "ColorMatrix2");
    const double t1 = dcp_illuminant_temperature(d.illuminant1), t2 = dcp_illuminant_temperature(d.illuminant2);
    if (d.illuminant1 == d.illuminant2 || (t1 > 0 && t1 == t2))
      throw Error(ErrorCode::SameIlluminant, "CalibrationIlluminant1 " + fmt_code(d.illuminant1) + " and CalibrationIlluminant2 " +
                                                 fmt_code(d.illuminant2) +
                                                 " are the same (colour temperature): DNG readers use only the first");
  }
  if (d.has_forward_matrix2) {
    if (!d.has_forward_matrix1) throw Error(ErrorCode::ProfileInvalid, "ForwardMatrix2 without ForwardMatrix1");
    if (!d.has_color_matrix2) throw Error(ErrorCode::ProfileInvalid, "ForwardMatrix2 without ColorMatrix2");
    check_matrix(d.forward_matrix2, "ForwardMatrix2");
  }
  check_table(d.hue_sat_map, "ProfileHueSatMap", d.has_color_matrix2);
  check_table(d.look_table, "ProfileLookTable", false);
  if (!d.tone_curve.empty()) {
    if (d.tone_curve.size() < 4 || d.tone_curve.size() % 2 != 0)
      throw Error(ErrorCode::ProfileInvalid, "ProfileToneCurve needs x,y pairs, at least two");
    for (std::size_t i = 0; i < d.tone_curve.size(); ++i) {
      const float v = d.tone_curve[i];
      if (!std::isfinite(v) || v < 0 || v > 1 || (i >= 2 && i % 2 == 0 && !(v > d.tone_curve[i - 2])))
        throw Error(ErrorCode::ProfileInvalid, "ProfileToneCurve: points must be in [0, 1] with x increasing");
    }
  }
  if (d.embed_policy > 3) throw Error(ErrorCode::ProfileInvalid, "ProfileEmbedPolicy " + std::to_string(d.embed_policy) + " (0..3)");
  if (d.has_baseline_exposure_offset && !std::isfinite(d.baseline_exposure_offset))
    throw Error(ErrorCode::ProfileInvalid, "BaselineExposureOffset is not finite");
}

// ---------------------------------------------------------------------------- writer

namespace {

using tiff::Field;
using tiff::put16;
using tiff::put32;

Field ascii(std::uint16_t tag, const std::string& s) {
  Field f{tag, kAscii, static_cast<std::uint32_t>(s.size() + 1), {}};
  f.bytes.assign(s.begin(), s.end());
  f.bytes.push_back(0);
  return f;
}

Field longs(std::uint16_t tag, std::initializer_list<std::uint32_t> v) {
  Field f{tag, kLong, static_cast<std::uint32_t>(v.size()), {}};
  for (auto x : v) put32(f.bytes, x);
  return f;
}

Field floats(std::uint16_t tag, const std::vector<float>& v) {
  Field f{tag, kFloat, static_cast<std::uint32_t>(v.size()), {}};
  f.bytes.reserve(v.size() * 4);
  for (float x : v) {
    std::uint32_t u;
    std::memcpy(&u, &x, 4);
    put32(f.bytes, u);
  }
  return f;
}

/// SRATIONAL with the largest power-of-ten denominator <= 10^6 that keeps the numerator in range
/// (the DNG SDK rounds ColorMatrix to 10^-4 on reading only when it normalises it; 10^-6 keeps
/// ForwardMatrix·(1,1,1) = D50 to 2e-6).
Field srationals(std::uint16_t tag, const Mat3& m) {
  Field f{tag, kSRational, 9, {}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double v = m(r, c);
      std::int64_t den = 1000000;
      while (den > 1 && std::abs(std::llround(v * static_cast<double>(den))) > std::numeric_limits<std::int32_t>::max()) den /= 10;
      const std::int64_t num = std::llround(v * static_cast<double>(den));
      if (std::abs(num) > std::numeric_limits<std::int32_t>::max())
        throw Error(ErrorCode::ProfileInvalid, "a matrix entry " + std::to_string(v) + " beyond an SRATIONAL");
      put32(f.bytes, static_cast<std::uint32_t>(static_cast<std::int32_t>(num)));
      put32(f.bytes, static_cast<std::uint32_t>(den));
    }
  return f;
}

}  // namespace

std::vector<std::uint8_t> write_dcp(const Dcp& d) {
  validate(d);
  if (d.has_baseline_exposure_offset || d.has_default_black_render || !d.look_table.empty())
    throw Error(ErrorCode::InvalidArgument, "the DCP writer writes no LookTable, BaselineExposureOffset or DefaultBlackRender");
  std::vector<Field> fields;
  fields.push_back(ascii(dcp_tag::UniqueCameraModel, d.unique_camera_model));
  fields.push_back(srationals(dcp_tag::ColorMatrix1, d.color_matrix1));
  if (d.has_color_matrix2) fields.push_back(srationals(dcp_tag::ColorMatrix2, d.color_matrix2));
  Field ill1{dcp_tag::CalibrationIlluminant1, kShort, 1, {}};
  put16(ill1.bytes, static_cast<std::uint32_t>(d.illuminant1));
  fields.push_back(ill1);
  if (d.has_color_matrix2) {
    Field ill2{dcp_tag::CalibrationIlluminant2, kShort, 1, {}};
    put16(ill2.bytes, static_cast<std::uint32_t>(d.illuminant2));
    fields.push_back(ill2);
  }
  if (!d.calibration_signature.empty()) fields.push_back(ascii(dcp_tag::ProfileCalibrationSignature, d.calibration_signature));
  if (!d.profile_name.empty()) fields.push_back(ascii(dcp_tag::ProfileName, d.profile_name));
  if (!d.hue_sat_map.empty()) {
    // Dims and Data1 always together (RawTherapee reads the data tag after the dims unchecked).
    fields.push_back(longs(dcp_tag::ProfileHueSatMapDims, {d.hue_sat_map.hue, d.hue_sat_map.sat, d.hue_sat_map.val}));
    fields.push_back(floats(dcp_tag::ProfileHueSatMapData1, d.hue_sat_map.data1));
    if (!d.hue_sat_map.data2.empty()) fields.push_back(floats(dcp_tag::ProfileHueSatMapData2, d.hue_sat_map.data2));
    fields.push_back(longs(dcp_tag::ProfileHueSatMapEncoding, {d.hue_sat_map.encoding}));
  }
  if (!d.tone_curve.empty()) fields.push_back(floats(dcp_tag::ProfileToneCurve, d.tone_curve));
  fields.push_back(longs(dcp_tag::ProfileEmbedPolicy, {d.embed_policy}));
  if (!d.copyright.empty()) fields.push_back(ascii(dcp_tag::ProfileCopyright, d.copyright));
  if (d.has_forward_matrix1) fields.push_back(srationals(dcp_tag::ForwardMatrix1, d.forward_matrix1));
  if (d.has_forward_matrix2) fields.push_back(srationals(dcp_tag::ForwardMatrix2, d.forward_matrix2));
  std::sort(fields.begin(), fields.end(), [](const Field& a, const Field& b) { return a.tag < b.tag; });

  // Header, the IFD at offset 8, then every value longer than 4 bytes at an even offset (TIFF 6.0
  // §2: values begin on a word boundary).
  std::vector<std::uint8_t> out = {'I', 'I', 'R', 'C'};
  put32(out, 8);
  tiff::append_ifd(out, fields, false, "DCP");
  return out;
}

// ---------------------------------------------------------------------------- reader

bool is_dcp(const std::uint8_t* b, std::size_t n) {
  return n >= 4 && ((b[0] == 'I' && b[1] == 'I' && b[2] == 'R' && b[3] == 'C') ||
                    (b[0] == 'M' && b[1] == 'M' && b[2] == 'C' && b[3] == 'R'));
}

namespace {

struct Reader {
  const std::uint8_t* b;
  std::size_t n;
  bool le;
  std::uint32_t u16(std::size_t at) const {
    if (at + 2 > n) throw Error(ErrorCode::ParseError, "DCP: truncated at byte " + std::to_string(at));
    return le ? (b[at] | b[at + 1] << 8) : (b[at] << 8 | b[at + 1]);
  }
  std::uint32_t u32(std::size_t at) const {
    const std::uint32_t x = u16(at), y = u16(at + 2);
    return le ? (x | y << 16) : (x << 16 | y);
  }
};

struct Entry {
  std::uint16_t type;
  std::uint32_t count;
  std::size_t at;  // where the values are
};

const char* tag_name(std::uint16_t tag) {
  switch (tag) {
    case dcp_tag::UniqueCameraModel: return "UniqueCameraModel";
    case dcp_tag::ColorMatrix1: return "ColorMatrix1";
    case dcp_tag::ColorMatrix2: return "ColorMatrix2";
    case dcp_tag::CalibrationIlluminant1: return "CalibrationIlluminant1";
    case dcp_tag::CalibrationIlluminant2: return "CalibrationIlluminant2";
    case dcp_tag::ProfileCalibrationSignature: return "ProfileCalibrationSignature";
    case dcp_tag::ProfileName: return "ProfileName";
    case dcp_tag::ProfileHueSatMapDims: return "ProfileHueSatMapDims";
    case dcp_tag::ProfileHueSatMapData1: return "ProfileHueSatMapData1";
    case dcp_tag::ProfileHueSatMapData2: return "ProfileHueSatMapData2";
    case dcp_tag::ProfileToneCurve: return "ProfileToneCurve";
    case dcp_tag::ProfileEmbedPolicy: return "ProfileEmbedPolicy";
    case dcp_tag::ProfileCopyright: return "ProfileCopyright";
    case dcp_tag::ForwardMatrix1: return "ForwardMatrix1";
    case dcp_tag::ForwardMatrix2: return "ForwardMatrix2";
    case dcp_tag::ProfileLookTableDims: return "ProfileLookTableDims";
    case dcp_tag::ProfileLookTableData: return "ProfileLookTableData";
    case dcp_tag::ProfileHueSatMapEncoding: return "ProfileHueSatMapEncoding";
    case dcp_tag::ProfileLookTableEncoding: return "ProfileLookTableEncoding";
    case dcp_tag::BaselineExposureOffset: return "BaselineExposureOffset";
    case dcp_tag::DefaultBlackRender: return "DefaultBlackRender";
    default: return nullptr;
  }
}

}  // namespace

Dcp read_dcp(const std::uint8_t* b, std::size_t n) {
  if (n == 0) throw Error(ErrorCode::EmptyFile, "DCP: empty file");
  if (n < 8 || !is_dcp(b, n))
    throw Error(ErrorCode::ParseError, "not a DCP: a DNG camera profile starts with \"IIRC\" or \"MMCR\" (DNG 1.6 chapter 7)");
  const Reader r{b, n, b[0] == 'I'};
  const std::size_t ifd = r.u32(4);
  if (ifd < 8 || ifd + 2 > n) throw Error(ErrorCode::ParseError, "DCP: the IFD offset " + std::to_string(ifd) + " is outside the file");
  const std::uint32_t count = r.u16(ifd);
  if (count == 0) throw Error(ErrorCode::ParseError, "DCP: an empty IFD");
  if (ifd + 2 + 12 * static_cast<std::size_t>(count) > n)
    throw Error(ErrorCode::ParseError, "DCP: the IFD's " + std::to_string(count) + " entries run past the end of the file");
  std::map<std::uint16_t, Entry> entries;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t e = ifd + 2 + 12 * static_cast<std::size_t>(i);
    const auto tag = static_cast<std::uint16_t>(r.u16(e));
    const auto type = static_cast<std::uint16_t>(r.u16(e + 2));
    const std::uint32_t cnt = r.u32(e + 4);
    const char* name = tag_name(tag);
    if (!name) continue;  // another tag: not ours to judge
    const std::size_t size = type_size(type);
    if (size == 0) throw Error(ErrorCode::ParseError, std::string("DCP: ") + name + " has an unknown type " + std::to_string(type));
    const std::uint64_t bytes = static_cast<std::uint64_t>(cnt) * size;
    const std::size_t at = bytes <= 4 ? e + 8 : r.u32(e + 8);
    if (bytes > n || at > n - bytes)
      throw Error(ErrorCode::ParseError, std::string("DCP: ") + name + "'s " + std::to_string(cnt) + " values lie outside the file");
    if (entries.count(tag)) throw Error(ErrorCode::ParseError, std::string("DCP: ") + name + " appears twice");
    entries[tag] = Entry{type, cnt, at};
  }
  auto find = [&](std::uint16_t tag) -> const Entry* {
    auto it = entries.find(tag);
    return it == entries.end() ? nullptr : &it->second;
  };
  auto want = [&](std::uint16_t tag, const Entry& e, std::initializer_list<std::uint16_t> types, std::uint32_t cnt) {
    if (std::find(types.begin(), types.end(), e.type) == types.end())
      throw Error(ErrorCode::ParseError, std::string("DCP: ") + tag_name(tag) + " has type " + std::to_string(e.type));
    if (cnt && e.count != cnt)
      throw Error(ErrorCode::ParseError, std::string("DCP: ") + tag_name(tag) + " has " + std::to_string(e.count) +
                                             " values, not " + std::to_string(cnt));
  };
  auto text = [&](std::uint16_t tag) -> std::string {
    const Entry* e = find(tag);
    if (!e) return "";
    want(tag, *e, {kAscii, kByte}, 0);  // DNG 1.6 allows BYTE (UTF-8) for the profile strings
    std::string s(reinterpret_cast<const char*>(b + e->at), e->count);
    while (!s.empty() && s.back() == '\0') s.pop_back();
    if (s.find('\0') != std::string::npos) s.resize(s.find('\0'));
    return s;
  };
  auto whole = [&](std::uint16_t tag, std::uint32_t fallback) -> std::uint32_t {
    const Entry* e = find(tag);
    if (!e) return fallback;
    want(tag, *e, {kShort, kLong}, 1);
    return e->type == kShort ? r.u16(e->at) : r.u32(e->at);
  };
  auto rational = [&](std::size_t at, bool is_signed, const char* name) {
    const std::uint32_t a = r.u32(at), d = r.u32(at + 4);
    const double num = is_signed ? static_cast<double>(static_cast<std::int32_t>(a)) : a;
    const double den = is_signed ? static_cast<double>(static_cast<std::int32_t>(d)) : d;
    if (den == 0) throw Error(ErrorCode::ProfileInvalid, std::string("DCP: ") + name + " has a zero denominator");
    return num / den;
  };
  auto matrix = [&](std::uint16_t tag, bool& present) {
    Mat3 m = Mat3::Identity();
    const Entry* e = find(tag);
    present = e != nullptr;
    if (!e) return m;
    want(tag, *e, {kSRational, kRational}, 0);
    if (e->count != 9)
      throw Error(ErrorCode::ProfileInvalid, std::string("DCP: ") + tag_name(tag) + " has " + std::to_string(e->count) +
                                                 " values: only 3-colour cameras (9 values) are supported");
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = rational(e->at + 8 * i, e->type == kSRational, tag_name(tag));
    return m;
  };
  auto float_array = [&](std::uint16_t tag) {
    std::vector<float> v;
    const Entry* e = find(tag);
    if (!e) return v;
    want(tag, *e, {kFloat}, 0);
    v.resize(e->count);
    for (std::uint32_t i = 0; i < e->count; ++i) {
      const std::uint32_t u = r.u32(e->at + 4 * static_cast<std::size_t>(i));
      std::memcpy(&v[i], &u, 4);
    }
    return v;
  };
  auto dims = [&](std::uint16_t tag, DcpHsvTable& t) {
    const Entry* e = find(tag);
    if (!e) return;
    want(tag, *e, {kLong}, 3);
    t.hue = r.u32(e->at);
    t.sat = r.u32(e->at + 4);
    t.val = r.u32(e->at + 8);
    if (t.hue == 0) throw Error(ErrorCode::ProfileInvalid, std::string("DCP: ") + tag_name(tag) + " has 0 hue divisions");
  };

  Dcp d;
  d.unique_camera_model = text(dcp_tag::UniqueCameraModel);
  d.profile_name = text(dcp_tag::ProfileName);
  d.copyright = text(dcp_tag::ProfileCopyright);
  d.calibration_signature = text(dcp_tag::ProfileCalibrationSignature);
  d.embed_policy = whole(dcp_tag::ProfileEmbedPolicy, 0);
  d.illuminant1 = static_cast<int>(whole(dcp_tag::CalibrationIlluminant1, 0));
  d.illuminant2 = static_cast<int>(whole(dcp_tag::CalibrationIlluminant2, 0));
  bool has_cm1 = false;
  d.color_matrix1 = matrix(dcp_tag::ColorMatrix1, has_cm1);
  if (!has_cm1) throw Error(ErrorCode::ProfileInvalid, "DCP without ColorMatrix1 (DNG 1.6: every camera profile has one)");
  d.color_matrix2 = matrix(dcp_tag::ColorMatrix2, d.has_color_matrix2);
  d.forward_matrix1 = matrix(dcp_tag::ForwardMatrix1, d.has_forward_matrix1);
  d.forward_matrix2 = matrix(dcp_tag::ForwardMatrix2, d.has_forward_matrix2);
  dims(dcp_tag::ProfileHueSatMapDims, d.hue_sat_map);
  d.hue_sat_map.data1 = float_array(dcp_tag::ProfileHueSatMapData1);
  d.hue_sat_map.data2 = float_array(dcp_tag::ProfileHueSatMapData2);
  d.hue_sat_map.encoding = whole(dcp_tag::ProfileHueSatMapEncoding, 0);
  dims(dcp_tag::ProfileLookTableDims, d.look_table);
  d.look_table.data1 = float_array(dcp_tag::ProfileLookTableData);
  d.look_table.encoding = whole(dcp_tag::ProfileLookTableEncoding, 0);
  d.tone_curve = float_array(dcp_tag::ProfileToneCurve);
  if (const Entry* e = find(dcp_tag::BaselineExposureOffset)) {
    want(dcp_tag::BaselineExposureOffset, *e, {kSRational}, 1);
    d.has_baseline_exposure_offset = true;
    d.baseline_exposure_offset = rational(e->at, true, "BaselineExposureOffset");
  }
  if (find(dcp_tag::DefaultBlackRender)) {
    d.has_default_black_render = true;
    d.default_black_render = whole(dcp_tag::DefaultBlackRender, 0);
  }
  if (d.has_color_matrix2 && !find(dcp_tag::CalibrationIlluminant2))
    throw Error(ErrorCode::ProfileInvalid, "DCP: ColorMatrix2 without CalibrationIlluminant2");
  validate(d);
  return d;
}

}  // namespace tristim

// DNG camera profiles (profile/dcp.hpp): the matrices derived from a profile, the file written
// and read back, the tags' numbers and types against the DNG 1.6 specification, dual-illuminant
// order and interpolation, the HueSatMap against the model through the DNG pipeline, and the
// reader's refusals. The clients (RawTherapee, ExifTool): dcp_clients_test.cpp.
#include <Eigen/LU>

#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <random>

#include "test_support.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/profile/profile.hpp"

using tristim::test::require_code;

using namespace tristim;

namespace {

/// A camera: camera RGB (DN) -> XYZ under D50 (Y = 100 for the perfect diffuser).
Mat3 camera_matrix() {
  Mat3 m;
  m << 0.0120, 0.0062, 0.0021,
       0.0051, 0.0151, -0.0008,
       0.0006, -0.0035, 0.0241;
  return m;
}

Profile matrix_profile(const Mat3& m, const Vec3& white, const std::string& illuminant) {
  Profile p;
  p.model.id = "matrix-3x3";
  p.model.coefficients = m;
  p.white = white;
  p.illuminant = illuminant;
  p.rgb_max = 6000;
  return p;
}

/// A degree-2 root-polynomial (Finlayson 2015) near camera_matrix(), white D50.
Profile root_profile(int degree = 2) {
  Profile p;
  p.model.id = "Finlayson2015-" + std::to_string(degree);
  const ModelInfo& info = model_info(p.model.id);
  p.model.coefficients = Eigen::MatrixXd::Zero(3, info.n_terms);
  p.model.coefficients.leftCols(3) = camera_matrix() * 0.8;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.002, 0.004);
  for (int t = 3; t < info.n_terms; ++t)
    for (int r = 0; r < 3; ++r) p.model.coefficients(r, t) = u(rng) * (r == t % 3 ? 1.5 : 0.5);
  p.white = whites::D50();
  p.illuminant = "D50";
  p.rgb_max = 6000;
  return p;
}

std::vector<std::uint8_t> bytes_of(const Dcp& d) { return write_dcp(d); }

/// IFD entries of a little-endian DCP, straight from the bytes: tag -> (type, count).
std::map<int, std::pair<int, std::uint32_t>> entries(const std::vector<std::uint8_t>& b) {
  auto u16 = [&](size_t at) { return static_cast<std::uint32_t>(b.at(at) | b.at(at + 1) << 8); };
  auto u32 = [&](size_t at) { return u16(at) | u16(at + 2) << 16; };
  std::map<int, std::pair<int, std::uint32_t>> out;
  const size_t ifd = u32(4);
  int last = -1;
  for (std::uint32_t i = 0, n = u16(ifd); i < n; ++i) {
    const size_t e = ifd + 2 + 12 * i;
    const int tag = static_cast<int>(u16(e));
    CHECK(tag > last);  // TIFF 6.0: entries in ascending tag order
    last = tag;
    out[tag] = {static_cast<int>(u16(e + 2)), u32(e + 4)};
  }
  return out;
}

}  // namespace

TEST_CASE("dcp: ForwardMatrix and ColorMatrix of a 3x3 profile follow DNG 1.6", "[dcp]") {
  const Mat3 m = camera_matrix();
  const Profile p = matrix_profile(m, whites::D50(), "D50");
  const DcpCalibration c = dcp_calibration(p);
  CHECK(c.illuminant.code == 23);
  // The camera white: the camera RGB the model maps to the profile white; neutral max 1.
  CHECK((m * c.camera_white - whites::D50()).norm() < 1e-9);
  CHECK(c.neutral.maxCoeff() == 1.0);
  // ForwardMatrix·(1,1,1) = D50 (the SDK's PCS white), and it is the model on white-balanced RGB.
  CHECK((c.forward_matrix * Vec3::Ones() - dcp_d50()).norm() < 1e-12);
  const Mat3 adapt = chromatic_adaptation_matrix(whites::D50() / 100.0, dcp_d50(), ChromaticAdaptation::Bradford);
  const Vec3 rgb(1200, 2500, 900);
  const Vec3 via_fm = c.forward_matrix * rgb.cwiseQuotient(c.camera_white);
  const Vec3 via_model = adapt * m * rgb / 100.0;
  CHECK((via_fm - via_model).norm() < 1e-6 * via_model.norm());
  // ColorMatrix: XYZ under the illuminant -> camera; the illuminant's white (Y = 1) -> the neutral.
  CHECK((c.color_matrix * whites::D50() / 100.0 - c.neutral).norm() < 1e-12);
  CHECK((c.color_matrix * m * rgb * (c.camera_white.maxCoeff() / 100.0) - rgb).norm() < 1e-9 * rgb.norm());
}

TEST_CASE("dcp: the file is IIRC with the camera profile tags of DNG 1.6 and reads back", "[dcp]") {
  const Profile p = root_profile();
  DcpOptions o;
  o.camera_model = "Canon EOS 550D";
  o.hue_sat_map = {36, 8, 1};
  const Dcp d = make_dcp(p, o);
  const std::vector<std::uint8_t> b = bytes_of(d);
  REQUIRE(b.size() > 8);
  CHECK(std::string(b.begin(), b.begin() + 4) == "IIRC");
  CHECK(is_dcp(b.data(), b.size()));
  // Tag numbers and types as DNG 1.6 chapter 4 lists them (exiftool 12.57 agrees): 2 ASCII,
  // 3 SHORT, 4 LONG, 10 SRATIONAL, 11 FLOAT.
  const auto e = entries(b);
  const std::map<int, std::pair<int, std::uint32_t>> want = {
      {50708, {2, 15}},          // UniqueCameraModel "Canon EOS 550D" + NUL
      {50721, {10, 9}},          // ColorMatrix1
      {50778, {3, 1}},           // CalibrationIlluminant1
      {50932, {2, 8}},           // ProfileCalibrationSignature "tristim"
      {50936, {2, static_cast<std::uint32_t>(d.profile_name.size() + 1)}},  // ProfileName
      {50937, {4, 3}},           // ProfileHueSatMapDims
      {50938, {11, 36 * 8 * 3}}, // ProfileHueSatMapData1
      {50941, {4, 1}},           // ProfileEmbedPolicy
      {50942, {2, static_cast<std::uint32_t>(d.copyright.size() + 1)}},  // ProfileCopyright
      {50964, {10, 9}},          // ForwardMatrix1
      {51107, {4, 1}},           // ProfileHueSatMapEncoding
  };
  CHECK(e == want);
  const Dcp r = read_dcp(b);
  CHECK(r.unique_camera_model == "Canon EOS 550D");
  CHECK(r.profile_name == "tristim Finlayson2015-2 ls D50");
  CHECK(r.calibration_signature == "tristim");
  CHECK(r.illuminant1 == 23);
  CHECK_FALSE(r.dual());
  CHECK((r.color_matrix1 - d.color_matrix1).cwiseAbs().maxCoeff() <= 5e-7);
  CHECK((r.forward_matrix1 - d.forward_matrix1).cwiseAbs().maxCoeff() <= 5e-7);
  CHECK(r.hue_sat_map.data1 == d.hue_sat_map.data1);
  CHECK(r.hue_sat_map.hue == 36);
  CHECK(r.hue_sat_map.sat == 8);
  CHECK(r.hue_sat_map.val == 1);
  CHECK(r.tone_curve.empty());
  CHECK(r.look_table.empty());
  CHECK(write_dcp(r) == b);  // a second round changes nothing
}

TEST_CASE("dcp: dual-illuminant, A first, each illuminant's white balance maps to neutral", "[dcp]") {
  // One camera under D65 and A: the camera's XYZ -> RGB is the same, the fits differ a little.
  const Mat3 m = camera_matrix();
  Mat3 m_a = m;
  m_a(0, 1) += 0.0004;
  m_a(2, 0) -= 0.0003;
  const Vec3 white_a = xyY_to_XYZ(Vec3(0.44757, 0.40745, 100));
  const Profile d65 = matrix_profile(m, whites::D65(), "D65");
  Profile a = matrix_profile(m_a, white_a, "custom");
  DcpOptions o;
  o.camera_model = "Test Camera";
  require_code([&] { make_dcp(d65, o, &a); }, ErrorCode::UnknownId);  // "custom": name the illuminant
  o.second_illuminant = "A";
  const Dcp d = make_dcp(d65, o, &a);
  CHECK(d.dual());
  CHECK(d.illuminant1 == 17);  // A: the lower temperature first, whatever the order given
  CHECK(d.illuminant2 == 21);
  const Dcp r = read_dcp(write_dcp(d));
  for (int k = 1; k <= 2; ++k) {
    const Vec3 white = k == 1 ? white_a / white_a[1] : whites::D65() / 100.0;
    const Mat3& cm = k == 1 ? r.color_matrix1 : r.color_matrix2;
    Vec3 neutral = cm * white;
    neutral /= neutral.maxCoeff();
    // The neutral is the profile's camera white.
    const DcpCalibration c = dcp_calibration(k == 1 ? a : d65, k == 1 ? "A" : "");
    CHECK((neutral - c.neutral).norm() < 1e-5);
    // Through a reader's pipeline (interpolated): the white found is the illuminant's, the weight
    // all but the illuminant's, and the neutral renders as D50.
    const DcpTransform t = dcp_camera_to_xyz(r, neutral, 0);
    const Eigen::Vector2d xy = XYZ_to_xy(white);
    INFO("illuminant " << k << ": white xy " << t.white_xy.transpose() << ", weight1 " << t.weight1);
    CHECK((t.white_xy - xy).norm() < 1e-4);
    CHECK(std::abs(t.weight1 - (k == 1 ? 1.0 : 0.0)) < 0.01);
    const Vec3 rendered = t.camera_to_xyz * neutral;
    CHECK((rendered - dcp_d50()).norm() < 1e-5);
  }
  // Halfway in inverse CCT the two are mixed.
  const Vec3 mid = xyY_to_XYZ(Vec3(0.3805, 0.3768, 1.0));  // ~4000 K
  Vec3 n = (0.5 * r.color_matrix1 + 0.5 * r.color_matrix2) * mid;
  n /= n.maxCoeff();
  const DcpTransform t = dcp_camera_to_xyz(r, n, 0);
  CHECK(t.weight1 > 0.2);
  CHECK(t.weight1 < 0.8);
  // Equal illuminants are refused, in the export and in a file.
  Profile b = matrix_profile(m_a, whites::D65(), "D65");
  o.second_illuminant = "";
  require_code([&] { make_dcp(d65, o, &b); }, ErrorCode::SameIlluminant);
  Dcp same = d;
  same.illuminant2 = 17;
  require_code([&] { write_dcp(same); }, ErrorCode::SameIlluminant);
}

TEST_CASE("dcp: the HueSatMap carries a root-polynomial through the DNG pipeline", "[dcp]") {
  const Profile p = root_profile();
  DcpOptions o;
  o.camera_model = "Test Camera";
  const Dcp plain = read_dcp(write_dcp(make_dcp(p, o)));
  o.hue_sat_map = {90, 30, 30};
  const Dcp mapped = read_dcp(write_dcp(make_dcp(p, o)));
  const DcpCalibration c = dcp_calibration(p);
  const Mat3 adapt = chromatic_adaptation_matrix(p.white / p.white[1], dcp_d50(), ChromaticAdaptation::Bradford);
  const DcpTransform t = dcp_camera_to_xyz(mapped, c.neutral, 1);
  const double scale = p.rgb_max, k = c.camera_white.maxCoeff() / (scale * p.white[1]);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.03, 0.9);
  // Camera colours whose ForwardMatrix rendering is inside ProPhoto (the map's domain: outside it
  // RawTherapee applies the matrix alone, the DNG SDK clips first).
  const Mat3 to_prophoto = prophoto_to_xyz().inverse();
  double mean_map = 0, max_map = 0, mean_plain = 0;
  const int n = 400;
  int outside = 0;
  for (int i = 0; i < n;) {
    const Vec3 dn(u(rng) * scale, u(rng) * scale, u(rng) * scale);
    if ((to_prophoto * (t.camera_to_xyz * dn / scale)).minCoeff() < 0) {
      ++outside;
      continue;
    }
    ++i;
    const Vec3 want = k * (adapt * predict(p.model, dn));
    const Vec3 a = dcp_render(mapped, t, dn / scale, true), b = dcp_render(plain, t, dn / scale, false);
    const Vec3 w = dcp_d50() * 100;
    const double de = delta_E_CIE2000(XYZ_to_Lab(a * 100, w), XYZ_to_Lab(want * 100, w));
    mean_map += de / n;
    max_map = std::max(max_map, de);
    mean_plain += delta_E_CIE2000(XYZ_to_Lab(b * 100, w), XYZ_to_Lab(want * 100, w)) / n;
  }
  INFO(outside << " colours outside ProPhoto skipped");
  INFO("HueSatMap 90x30x30: mean dE00 " << mean_map << ", max " << max_map << "; ForwardMatrix only: mean " << mean_plain);
  CHECK(mean_map < 0.05);
  CHECK(max_map < 2.0);  // 1.46: a blue of ProPhoto saturation 0.92, where the root terms bend fastest between nodes
  CHECK(mean_plain > 4 * mean_map);
  // The neutral axis is left alone: saturation 0 has no hue shift and unit scales.
  for (std::uint32_t h = 0; h < 90; ++h) {
    const float* e = &mapped.hue_sat_map.data1[3 * (h * 30)];
    CHECK(e[0] == 0.0f);
    CHECK(e[1] == 1.0f);
    CHECK(std::abs(e[2] - 1.0f) < 1e-5f);
  }
}

TEST_CASE("dcp: a 90x30x30 HueSatMap of a degree-3 root-polynomial", "[dcp]") {
  // Its time is a benchmark (tests/bench/bench_export.cpp), never asserted here.
  const Profile p = root_profile(3);
  DcpOptions o;
  o.camera_model = "Test Camera";
  o.hue_sat_map = {90, 30, 30};
  const Dcp d = make_dcp(p, o);
  CHECK(d.hue_sat_map.data1.size() == 90u * 30 * 30 * 3);
  CHECK(read_dcp(write_dcp(d)).hue_sat_map.data1 == d.hue_sat_map.data1);
}

TEST_CASE("dcp: refusals of the export", "[dcp]") {
  const Profile p = matrix_profile(camera_matrix(), whites::D50(), "D50");
  DcpOptions o;
  require_code([&] { make_dcp(p, o); }, ErrorCode::InvalidArgument);  // no camera model
  o.camera_model = "X";
  o.hue_sat_map = {90, 1, 1};
  require_code([&] { make_dcp(p, o); }, ErrorCode::InvalidArgument);  // saturation needs 2 divisions
  o.hue_sat_map = {0, 0, 0};
  o.illuminant = "E";
  require_code([&] { make_dcp(p, o); }, ErrorCode::UnknownId);  // no LightSource code for E
  o.illuminant = "";
  Profile lin = p;
  lin.has_linearisation = true;
  lin.linearisation.choice.method = "sRGB";
  require_code([&] { make_dcp(lin, o); }, ErrorCode::InvalidArgument);  // stored values, not RAW
  Dcp d = make_dcp(p, o);
  d.hue_sat_map.hue = 6;  // dims without data are never written
  d.hue_sat_map.sat = 6;
  d.hue_sat_map.val = 1;
  require_code([&] { write_dcp(d); }, ErrorCode::ProfileInvalid);
}

TEST_CASE("dcp: the reader refuses broken files with coded errors", "[dcp]") {
  const Profile p = matrix_profile(camera_matrix(), whites::D50(), "D50");
  DcpOptions o;
  o.camera_model = "X";
  o.hue_sat_map = {6, 3, 1};
  const std::vector<std::uint8_t> good = write_dcp(make_dcp(p, o));
  const auto e = entries(good);
  auto with = [&](const std::function<void(std::vector<std::uint8_t>&)>& f) {
    std::vector<std::uint8_t> b = good;
    f(b);
    return b;
  };
  // Renames the tag `from` in the IFD to `to` (an unknown tag, which the reader skips).
  auto rename = [&](std::vector<std::uint8_t>& b, int from, int to) {
    const size_t ifd = b[4] | b[5] << 8;
    for (size_t i = 0, n = b[ifd] | b[ifd + 1] << 8; i < n; ++i) {
      const size_t at = ifd + 2 + 12 * i;
      if ((b[at] | b[at + 1] << 8) == from) {
        b[at] = static_cast<std::uint8_t>(to);
        b[at + 1] = static_cast<std::uint8_t>(to >> 8);
      }
    }
  };
  require_code([&] { read_dcp(std::vector<std::uint8_t>{}); }, ErrorCode::EmptyFile);
  require_code([&] { read_dcp(with([](auto& b) { b[2] = '*'; b[3] = 0; })); }, ErrorCode::ParseError);  // a TIFF, not a DCP
  require_code([&] { read_dcp(std::vector<std::uint8_t>(good.begin(), good.begin() + 40)); }, ErrorCode::ParseError);
  require_code([&] { read_dcp(with([](auto& b) { b[4] = 0xff; b[5] = 0xff; })); }, ErrorCode::ParseError);
  require_code([&] { read_dcp(with([&](auto& b) { rename(b, 50721, 50720); })); }, ErrorCode::ProfileInvalid);  // no ColorMatrix1
  require_code([&] { read_dcp(with([&](auto& b) { rename(b, 50938, 50900); })); }, ErrorCode::ProfileInvalid);  // Dims without Data
  require_code([&] { read_dcp(with([&](auto& b) { rename(b, 50937, 50900); })); }, ErrorCode::ProfileInvalid);  // Data without Dims
  CHECK(e.count(50721) == 1);
  // Two equal illuminants: the dual file with illuminant 2 set to illuminant 1's code.
  Profile a = matrix_profile(camera_matrix(), xyY_to_XYZ(Vec3(0.44757, 0.40745, 100)), "custom");
  o.second_illuminant = "A";
  o.hue_sat_map = {0, 0, 0};
  std::vector<std::uint8_t> dual = write_dcp(make_dcp(p, o, &a));
  CHECK(read_dcp(dual).dual());
  const size_t ifd = dual[4] | dual[5] << 8;
  for (size_t i = 0, n = dual[ifd] | dual[ifd + 1] << 8; i < n; ++i) {
    const size_t at = ifd + 2 + 12 * i;
    if ((dual[at] | dual[at + 1] << 8) == 50779) dual[at + 8] = 17;  // CalibrationIlluminant2 := A (17) like 1
  }
  require_code([&] { read_dcp(dual); }, ErrorCode::SameIlluminant);
  // Every truncation of a good file is refused with a code, never read past its end.
  for (size_t n = 0; n < good.size(); n += 7) {
    const std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    const ErrorCode code = tristim::test::code_of([&] { read_dcp(cut); });
    CHECK((code == ErrorCode::ParseError || code == ErrorCode::EmptyFile || code == ErrorCode::ProfileInvalid));
  }
}

// The .cube and ICC header readers (tristim/profile/headers.hpp): planted — the engine's own
// exports read back with the sizes, shaper, classes and spaces export.hpp states — and refused
// inputs, each coded and naming the file (and the line for a .cube).
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "tristim/error.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/headers.hpp"
#include "tristim/profile/profile.hpp"

using namespace tristim;

namespace {

Profile small_profile() {
  Profile p;
  p.model.id = "matrix-3x3";
  p.model.coefficients = Eigen::MatrixXd::Identity(3, 3);
  p.white = Vec3(95.047, 100, 108.883);
  p.rgb_max = 1;
  return p;
}

ErrorCode code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return ErrorCode::Internal;
}

}  // namespace

TEST_CASE("cube header: the engine's .cube reads back with its shaper and 3D sizes") {
  for (int size : {2, 17}) {
    const std::string text = export_cube(small_profile(), size);
    const CubeHeader h = read_cube_header(text, "p.cube");
    CHECK(h.size == size);
    CHECK(h.shaper_size == kCubeShaperSize);
    CHECK(h.entries == std::int64_t(size) * size * size);
    CHECK(h.domain_min == std::array<double, 3>{0, 0, 0});
    CHECK(h.domain_max == std::array<double, 3>{1, 1, 1});
  }
  const CubeHeader t = read_cube_header("# c\r\nTITLE \"grey LUT\"\r\nDOMAIN_MIN 0 0 0\r\nDOMAIN_MAX 2 2 2\r\nLUT_3D_SIZE 2\r\n"
                                        "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n",
                                        "t.cube");
  CHECK(t.title == "grey LUT");
  CHECK(t.shaper_size == 0);
  CHECK(t.entries == 8);
  CHECK(t.domain_max == std::array<double, 3>{2, 2, 2});
}

TEST_CASE("cube header: malformed files are refused, coded, naming the file and line") {
  const std::string rows8 = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
  auto message = [](const std::string& text) {
    try {
      read_cube_header(text, "bad.cube");
    } catch (const Error& e) {
      CHECK(e.code() == ErrorCode::ParseError);
      return std::string(e.what());
    }
    FAIL("accepted: " << text);
    return std::string();
  };
  CHECK(message("LUT_3D_SIZE 2\n0 0 0\n") == "bad.cube: 1 table rows, expected 2³ = 8");
  CHECK(message(rows8) == "bad.cube: no LUT_3D_SIZE line");
  CHECK(message("LUT_3D_SIZE 2\n0 0 x\n") == "bad.cube: line 2: 'x' is not a finite number");
  CHECK(message("LUT_3D_SIZE 2\n0 0\n") == "bad.cube: line 2: expected three numbers, got 2 words");
  CHECK(message("LUT_3D_SIZE 1\n0 0 0\n") == "bad.cube: line 1: LUT_3D_SIZE must be a whole number from 2 to 256");
  CHECK(message("LUT_3D_SIZE 2.5\n") == "bad.cube: line 1: LUT_3D_SIZE must be a whole number from 2 to 256");
  CHECK(message("LUT_3D_SIZE 2\nDOMAIN_MIN 0 0\n" + rows8) == "bad.cube: line 2: expected 3 numbers after DOMAIN_MIN");
  CHECK(message("LUT_3D_SIZE 2\nDOMAIN_MAX 1 0 1\n" + rows8) == "bad.cube: DOMAIN_MIN must be below DOMAIN_MAX in each channel");
  CHECK(message("LUT_3D_SIZE 2\n1e999 0 0\n") == "bad.cube: line 2: '1e999' is not a finite number");
}

TEST_CASE("ICC header: the engine's ICC export reads back as a v4 scanner profile, RGB to its PCS") {
  const std::vector<std::uint8_t> icc = export_icc(small_profile());
  const IccHeader h = read_icc_header(icc, "p.icc");
  CHECK(h.size == std::int64_t(icc.size()));
  CHECK(h.version.rfind("4.", 0) == 0);
  CHECK(h.device_class == "scnr");
  CHECK(h.colour_space == "RGB");
  CHECK((h.pcs == "XYZ" || h.pcs == "Lab"));
  CHECK(!h.description.empty());
  std::string all;
  for (const auto& t : h.tags) all += t + " ";
  INFO("tags: " << all);
  for (const char* tag : {"desc", "cprt", "wtpt"})  // a 3 × 3 model: a matrix/TRC profile (rXYZ, rTRC, …)
    CHECK(std::find(h.tags.begin(), h.tags.end(), tag) != h.tags.end());
  CHECK(std::find(h.tags.begin(), h.tags.end(), "rXYZ") != h.tags.end());
}

TEST_CASE("ICC header: short, unsigned, mis-sized and corrupt profiles are refused, coded") {
  const std::vector<std::uint8_t> icc = export_icc(small_profile());
  CHECK(code_of([] { read_icc_header(std::vector<std::uint8_t>(10), "x.icc"); }) == ErrorCode::ParseError);
  auto unsigned_ = icc;
  unsigned_[36] = 'x';
  CHECK(code_of([&] { read_icc_header(unsigned_, "x.icc"); }) == ErrorCode::ParseError);
  auto cut = icc;
  cut.resize(icc.size() - 4);
  CHECK(code_of([&] { read_icc_header(cut, "x.icc"); }) == ErrorCode::ParseError);
  try {
    read_icc_header(cut, "cut.icc");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).rfind("cut.icc: the header says", 0) == 0);
  }
  auto tags = icc;  // a tag count far beyond the file
  tags[128] = tags[129] = 0x7F;
  CHECK(code_of([&] { read_icc_header(tags, "x.icc"); }) == ErrorCode::ParseError);
}

// RAW decoding: planted DNGs through LibRaw, the three real files, every bad input's code.
#include <cstring>
#include <random>

#include "test_support.hpp"
#include "dng_writer.hpp"
#include "tristim/error.hpp"
#include "tristim/capture/raw.hpp"

using namespace tristim;

namespace {

const char* kPassport = test::passport_dng;
const char* kCr2 = test::debian::canon_30d_cr2;
const char* kKdc = test::kodak_dc50_kdc;

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

ErrorCode decode_code(const std::vector<std::uint8_t>& b, const DecodeOptions& o = {}) {
  try {
    decode_raw(b, o);
  } catch (const Error& e) {
    return e.code();
  }
  FAIL("expected a coded error");
  return ErrorCode::Internal;
}

}  // namespace

TEST_CASE("a planted DNG decodes to exact half-resolution linear RGB", "[raw]") {
  for (const std::string cfa : {"RGGB", "BGGR", "GRBG", "GBRG"}) {
    const int W = 40, H = 30;
    const std::uint16_t black = 512, white = 15000;
    std::vector<std::uint16_t> v(W * H);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> dist(black, white);
    for (auto& x : v) x = static_cast<std::uint16_t>(dist(rng));
    v[0] = white;  // top-left sensor pixel saturated
    DngWriteOptions o;
    o.cfa = cfa;
    o.black = black;
    o.white = white;
    o.make = "Planted";
    o.model = cfa;
    const RawImage img = decode_raw(write_dng(v, W, H, o));
    INFO("CFA " << cfa);
    REQUIRE(img.width == W / 2);
    REQUIRE(img.height == H / 2);
    CHECK(img.meta.cfa_pattern == cfa);
    CHECK(img.meta.layout == "bayer");
    CHECK(img.meta.make == "Planted");
    CHECK(img.meta.white_level == white);
    CHECK(img.meta.black_level[1] == black);
    CHECK(img.meta.saturation[0] == white - black);
    const auto ch = [&](char c) { return c == 'R' ? 0 : c == 'G' ? 1 : 2; };
    for (int y = 0; y < H / 2; ++y)
      for (int x = 0; x < W / 2; ++x) {
        double expect[3] = {0, 0, 0}, count[3] = {0, 0, 0};
        std::uint8_t sat = 0;
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) {
            const int k = ch(cfa[r * 2 + c]);
            const double val = v[(2 * y + r) * W + 2 * x + c] - double(black);
            expect[k] += val;
            count[k] += 1;
            if (val >= 0.98 * (white - black)) sat |= 1 << k;
          }
        for (int k = 0; k < 3; ++k) REQUIRE(img.at(x, y, k) == Approx(expect[k] / count[k]).margin(1e-3));
        REQUIRE(img.saturated[y * img.width + x] == sat);
      }
    CHECK((img.saturated[0] & (1 << ch(cfa[0]))) != 0);
  }
}

TEST_CASE("an odd-sized DNG drops the incomplete last block", "[raw]") {
  std::vector<std::uint16_t> v(45 * 33, 1000);  // LibRaw refuses images under 22 pixels
  const RawImage img = decode_raw(write_dng(v, 45, 33));
  CHECK(img.width == 22);
  CHECK(img.height == 16);
}

TEST_CASE("the three real RAW files decode, with the same linear data in every build", "[raw][real]") {
  struct Case {
    const char* file;
    const char* make;
    int width, height;
    const char* cfa;
    const char* hash;  // FNV-1a of the linear data, recorded from the native build
  };
  const Case cases[] = {
      {kPassport, "Canon", 867, 578, "RGGB", "7509a785b9c2f349"},
      {kCr2, "Canon", 1761, 1174, "RGGB", "2db01d705f5a94f5"},
      {kKdc, "Kodak", 384, 256, "GRBG", "ede561aaf256d76e"},
  };
  for (const auto& c : cases) {
    INFO(c.file);
    const RawImage img = decode_raw(bytes_of(test::read_test_file(c.file)));
    CHECK(img.meta.make == c.make);
    CHECK(img.width == c.width);
    CHECK(img.height == c.height);
    CHECK(img.meta.cfa_pattern == c.cfa);
    CHECK(img.rgb.size() == size_t(c.width) * c.height * 3);
    CHECK(hash_hex(linear_data_hash(img)) == c.hash);
  }
}

TEST_CASE("Passport DNG metadata: levels and matrices", "[raw][real]") {
  const RawImage img = decode_raw(bytes_of(test::read_test_file(kPassport)));
  const auto& m = img.meta;
  CHECK(m.model == "EOS Kiss X4");
  CHECK(m.bits == 14);
  CHECK(m.black_level[0] == 2056);
  CHECK(m.white_level == 15000);
  CHECK(m.sensor_width == 1734);
  CHECK(m.sensor_height == 1156);
  // rgb_cam rows sum to 1 (LibRaw normalises camera white to sRGB white).
  for (int r = 0; r < 3; ++r) CHECK(m.rgb_cam[r * 3] + m.rgb_cam[r * 3 + 1] + m.rgb_cam[r * 3 + 2] == Approx(1).margin(1e-3));
  CHECK(m.cam_xyz[0] != 0);  // DNG ColorMatrix1
  const std::string json = metadata_to_json(m);
  CHECK(json.find("\"make\":\"Canon\"") != std::string::npos);
  CHECK(json.find("\"cfa_pattern\":\"RGGB\"") != std::string::npos);
}

TEST_CASE("CR2 metadata: exposure, lens, timestamp", "[raw][real]") {
  const RawImage img = decode_raw(bytes_of(test::read_test_file(kCr2)));
  const auto& m = img.meta;
  CHECK(m.model == "EOS 30D");
  CHECK(m.iso == Approx(640));
  CHECK(m.shutter_s == Approx(0.0025));
  CHECK(m.f_number == Approx(22));
  CHECK(m.lens == "EF-S 18-55mm f/3.5-5.6");
  CHECK(m.timestamp_iso == "2009-07-21T13:03:20");
  CHECK(m.white_level == 4095);
}

TEST_CASE("the preview is small, opaque and not the measurement data", "[raw]") {
  const RawImage img = decode_raw(bytes_of(test::read_test_file(kPassport)));
  const Preview pv = render_preview(img, 300);
  CHECK(pv.scale == 3);
  CHECK(pv.width == 867 / 3);
  CHECK(pv.height == 578 / 3);
  REQUIRE(pv.rgba.size() == size_t(pv.width) * pv.height * 4);
  bool any_bright = false;
  for (size_t i = 0; i < pv.rgba.size(); i += 4) {
    REQUIRE(pv.rgba[i + 3] == 255);
    any_bright = any_bright || pv.rgba[i + 1] > 128;
  }
  CHECK(any_bright);
  CHECK_THROWS_AS(render_preview(img, 0), Error);
}

TEST_CASE("a strip thinner than the preview's scale is previewed from its own rows", "[raw][bad]") {
  // 1000 x 3 stored (display-encoded) values, 8-bit scale: the preview at 64 px has scale 16 and
  // one row, which must average the strip's 3 rows only (it averaged 16, reading past the end of
  // the image; fuzz_raw found it with an 8076 x 11 Rollei strip).
  RawImage img;
  img.width = 1000;
  img.height = 3;
  img.meta.encoding = "stored";
  img.meta.white_level = 255;
  img.rgb.assign(static_cast<size_t>(img.width) * img.height * 3, 0.f);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) img.rgb[(static_cast<size_t>(y) * img.width + x) * 3 + c] = 51.f * (c + 1) + 10.f * y;
  img.saturated.assign(static_cast<size_t>(img.width) * img.height, 0);
  const Preview pv = render_preview(img, 64);
  CHECK(pv.scale == 16);
  CHECK(pv.width == 62);
  REQUIRE(pv.height == 1);
  for (int i = 0; i < pv.width; ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(int(pv.rgba[static_cast<size_t>(i) * 4 + c]) == 51 * (c + 1) + 10);
  // The linear path takes the same blocks: a flat strip stays flat (no dark preview row).
  img.meta.encoding = "linear";
  img.meta.saturation = {255, 255, 255};
  std::fill(img.rgb.begin(), img.rgb.end(), 100.f);
  const Preview lin = render_preview(img, 64);
  REQUIRE(lin.height == 1);
  for (int i = 1; i < lin.width; ++i) REQUIRE(lin.rgba[static_cast<size_t>(i) * 4] == lin.rgba[0]);
}

TEST_CASE("bad RAW input gives a coded error, never a crash", "[raw][bad]") {
  SECTION("zero bytes") { CHECK(decode_code({}) == ErrorCode::EmptyFile); }
  SECTION("truncated DNG: the first 1 MB") {
    auto b = bytes_of(test::read_test_file(kPassport));
    b.resize(1 << 20);
    CHECK(decode_code(b) == ErrorCode::RawTruncated);
  }
  SECTION("truncated CR2 (lossless JPEG)") {
    auto b = bytes_of(test::read_test_file(kCr2));
    b.resize(b.size() / 2);
    CHECK(decode_code(b) == ErrorCode::RawTruncated);
  }
  SECTION("a JPEG renamed .CR2") {
    CHECK(decode_code(bytes_of(test::read_test_file(test::passport_jpeg))) ==
          ErrorCode::RawUnsupported);
  }
  SECTION("a PNG renamed .CR2") {
    const std::uint8_t png[] = {137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 1, 0,
                                0, 0, 1, 8, 2, 0, 0, 0, 144, 119, 83, 222, 0, 0, 0, 12, 73, 68, 65, 84, 120,
                                156, 99, 248, 207, 192, 0, 0, 3, 1, 1, 0, 201, 254, 146, 239, 0, 0, 0, 0, 73,
                                69, 78, 68, 174, 66, 96, 130};
    CHECK(decode_code(std::vector<std::uint8_t>(png, png + sizeof png)) == ErrorCode::RawUnsupported);
  }
  SECTION("random bytes") {
    std::mt19937 rng(42);
    std::vector<std::uint8_t> b(1000003);
    for (auto& x : b) x = static_cast<std::uint8_t>(rng());
    CHECK(decode_code(b) == ErrorCode::RawUnsupported);
  }
  SECTION("a few bytes") { CHECK(decode_code({'I', 'I', 42, 0}) == ErrorCode::RawUnsupported); }
  SECTION("a DNG header claiming 60000 x 60000 pixels") {
    DngWriteOptions o;
    o.header_width = 60000;
    o.header_height = 60000;
    CHECK(decode_code(write_dng(std::vector<std::uint16_t>(64 * 48, 100), 64, 48, o)) == ErrorCode::RawTooLarge);
  }
  SECTION("a DNG header claiming more pixels than its data holds") {
    DngWriteOptions o;
    o.header_width = 6000;
    o.header_height = 4000;
    CHECK(decode_code(write_dng(std::vector<std::uint16_t>(64 * 48, 100), 64, 48, o)) == ErrorCode::RawTruncated);
  }
  SECTION("a file over the configured pixel limit") {
    DecodeOptions small;
    small.max_megapixels = 0.001;
    CHECK(decode_code(write_dng(std::vector<std::uint16_t>(64 * 48, 100), 64, 48), small) == ErrorCode::RawTooLarge);
  }
}

TEST_CASE("X-Trans (6x6 CFA): each 3x3 block becomes one pixel with its R, G, B means", "[raw]") {
  const std::string xt = "GGRGGB" "GGBGGR" "BRGRBG" "GGBGGR" "GGRGGB" "RBGBRG";
  const int W = 60, H = 48;
  std::vector<std::uint16_t> v(W * H);
  std::mt19937 rng(3);
  for (auto& x : v) x = static_cast<std::uint16_t>(200 + rng() % 9000);
  DngWriteOptions o;
  o.cfa = xt;
  o.black = 200;
  o.white = 16000;
  const RawImage img = decode_raw(write_dng(v, W, H, o));
  CHECK(img.meta.layout == "xtrans");
  CHECK(img.meta.block == 3);
  CHECK(img.meta.cfa_pattern == xt);
  REQUIRE(img.width == W / 3);
  REQUIRE(img.height == H / 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      double sum[3] = {0, 0, 0}, n[3] = {0, 0, 0};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const int row = 3 * y + r, col = 3 * x + c;
          const char letter = xt[(row % 6) * 6 + col % 6];
          const int k = letter == 'R' ? 0 : letter == 'G' ? 1 : 2;
          sum[k] += v[row * W + col] - 200.0;
          n[k] += 1;
        }
      for (int k = 0; k < 3; ++k) REQUIRE(img.at(x, y, k) == Approx(sum[k] / n[k]).margin(1e-3));
    }
}

TEST_CASE("4-colour CFAs are refused with RAW_UNSUPPORTED", "[raw][bad]") {
  for (const std::string cfa : {"CYGM", "RGBC"}) {
    DngWriteOptions o;
    o.cfa = cfa;
    INFO(cfa);
    CHECK(decode_code(write_dng(std::vector<std::uint16_t>(60 * 48, 1000), 60, 48, o)) == ErrorCode::RawUnsupported);
  }
}

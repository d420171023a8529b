// Images in (capture/image.hpp): TIFF, PNG and JPEG written at test time with the same libraries,
// their stored values back exactly (JPEG within its quantisation), a chart in an 8-bit TIFF
// sampled to its planted means, format detection by magic bytes, and every refusal's code.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <random>

#include "image_writer.hpp"
#include "test_support.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/error.hpp"

using namespace tristim;
using tristim::test::require_code;
using tristim::test::TestImage;

namespace {

const char* kJpeg = test::passport_jpeg;
const char* kPassport = test::passport_dng;
const char* kCr2 = test::debian::canon_30d_cr2;
const char* kKdc = test::kodak_dc50_kdc;

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

TestImage random_image(int w, int h, int channels, int bits, unsigned seed) {
  std::mt19937 rng(seed);
  const int top = (1 << bits) - 1;
  std::uniform_int_distribution<int> d(0, top);
  TestImage im = test::make_image(w, h, channels, bits, [&](int, int, int) { return d(rng); });
  im.at(0, 0, 0) = static_cast<std::uint16_t>(top);  // one clipped sample
  return im;
}

/// Every stored sample back exactly (grey to R = G = B), clipped samples flagged.
void require_exact(const RawImage& img, const TestImage& im) {
  REQUIRE(img.width == im.width);
  REQUIRE(img.height == im.height);
  const std::uint32_t top = (1u << im.bits) - 1;
  int worst = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::uint16_t v = im.samples[(static_cast<std::size_t>(y) * im.width + x) * im.channels +
                                           (im.channels == 1 ? 0 : c)];
        if (img.at(x, y, c) != static_cast<float>(v) && worst++ == 0)
          FAIL_CHECK("pixel (" << x << ", " << y << ") channel " << c << ": " << img.at(x, y, c) << " != " << v);
        const bool sat = (img.saturated[static_cast<std::size_t>(y) * im.width + x] >> c) & 1;
        if (sat != (v == top) && worst++ == 0) FAIL_CHECK("saturation bit of (" << x << ", " << y << ", " << c << ")");
      }
  CHECK(worst == 0);
}

void check_meta(const RawImage& img, const char* format, int bits, int channels) {
  CHECK(img.meta.format == format);
  CHECK(img.meta.encoding == "stored");
  CHECK(img.meta.bits == bits);
  CHECK(img.meta.white_level == (bits == 16 ? 65535.0 : 255.0));
  CHECK(img.meta.saturation[1] == img.meta.white_level);
  CHECK(img.meta.black_level[0] == 0.0);
  CHECK(img.meta.layout == (channels == 1 ? "monochrome" : "rgb"));
  CHECK(img.meta.width == img.width);
}

std::uint32_t crc32_of(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}
void put_be32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) b[at + k] = static_cast<std::uint8_t>(v >> (24 - 8 * k));
}
/// A PNG whose IHDR claims width × height (CRC fixed, so libpng reads the claim).
std::vector<std::uint8_t> png_claiming(std::vector<std::uint8_t> b, std::uint32_t w, std::uint32_t h) {
  put_be32(b, 16, w);
  put_be32(b, 20, h);
  put_be32(b, 29, crc32_of(&b[12], 17));
  return b;
}
/// Offset of the first SOFn marker's segment (after FF Cn) in a JPEG.
std::size_t jpeg_sof(const std::vector<std::uint8_t>& b) {
  for (std::size_t i = 2; i + 9 < b.size(); ++i)
    if (b[i] == 0xFF && b[i + 1] >= 0xC0 && b[i + 1] <= 0xC3) return i + 2;
  FAIL("no SOF marker");
  return 0;
}
/// Sets a SHORT tag's value in IFD0 of a little-endian TIFF (written by test::write_tiff).
std::vector<std::uint8_t> tiff_with_short(std::vector<std::uint8_t> b, std::uint16_t tag, std::uint16_t value) {
  const std::uint32_t ifd = b[4] | b[5] << 8 | b[6] << 16 | static_cast<std::uint32_t>(b[7]) << 24;
  const int n = b[ifd] | b[ifd + 1] << 8;
  for (int i = 0; i < n; ++i) {
    const std::size_t e = ifd + 2 + 12 * i;
    if ((b[e] | b[e + 1] << 8) == tag) {
      b[e + 8] = static_cast<std::uint8_t>(value & 255);
      b[e + 9] = static_cast<std::uint8_t>(value >> 8);
      return b;
    }
  }
  FAIL("tag " << tag << " not in IFD0");
  return b;
}

}  // namespace

TEST_CASE("TIFF: 8 and 16-bit grey and RGB samples come back exactly, in every layout", "[image]") {
  struct Case {
    const char* name;
    test::TiffWriteOptions o;
  };
  std::vector<Case> cases;
  cases.push_back({"uncompressed", {}});
  {
    test::TiffWriteOptions o;
    o.compression = 5;  // LZW
    o.predictor = 2;
    o.rows_per_strip = 3;
    cases.push_back({"LZW + horizontal predictor, 3-row strips", o});
  }
  {
    test::TiffWriteOptions o;
    o.compression = 8;  // Deflate
    o.planar_separate = true;
    cases.push_back({"Deflate, planar", o});
  }
  {
    test::TiffWriteOptions o;
    o.compression = 32773;  // PackBits
    o.tile = 16;
    o.big_endian = true;
    cases.push_back({"PackBits, 16x16 tiles, big-endian", o});
  }
  {
    test::TiffWriteOptions o;
    o.big_tiff = true;
    o.tile = 32;
    o.planar_separate = true;
    cases.push_back({"BigTIFF, planar tiles", o});
  }
  for (int bits : {8, 16})
    for (int channels : {1, 3})
      for (const auto& c : cases) {
        INFO(c.name << ", " << bits << "-bit, " << channels << " channel(s)");
        const TestImage im = random_image(37, 23, channels, bits, 11u * bits + channels);
        const auto file = test::write_tiff(im, c.o);
        CHECK(detect_format(file.data(), file.size()) == FileFormat::Tiff);
        const RawImage img = decode_any(file);
        check_meta(img, "tiff", bits, channels);
        require_exact(img, im);
      }
}

TEST_CASE("TIFF: tags read, colour declarations reported and not applied", "[image]") {
  const TestImage im = random_image(8, 6, 3, 16, 3);
  test::TiffWriteOptions o;
  o.make = "Scanner Co";
  o.model = "Flatbed 9";
  o.datetime = "2024:05:17 10:11:12";
  o.orientation = 6;  // 90° clockwise: LibRaw flip 6
  o.icc = std::vector<std::uint8_t>(500, 7);
  const RawImage img = decode_tiff(test::write_tiff(im, o).data(), test::write_tiff(im, o).size());
  CHECK(img.meta.make == "Scanner Co");
  CHECK(img.meta.model == "Flatbed 9");
  CHECK(img.meta.timestamp_iso == "2024-05-17T10:11:12");
  CHECK(img.meta.flip == 6);
  CHECK(img.meta.declared_colour == "ICC profile (500 bytes)");
  require_exact(img, im);  // the profile is not applied
}

TEST_CASE("TIFF: JPEG-compressed (YCbCr) strips decode to RGB within quantisation", "[image]") {
  const TestImage im = test::make_image(48, 32, 3, 8, [](int x, int y, int c) { return 40 + 2 * x + y + 30 * c; });
  test::TiffWriteOptions o;
  o.compression = 7;
  o.jpeg_quality = 100;
  o.jpeg_ycbcr = true;
  o.rows_per_strip = 16;
  const RawImage img = decode_any(test::write_tiff(im, o));
  check_meta(img, "tiff", 8, 3);
  double worst = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(img.at(x, y, c) - double(im.samples[(y * im.width + x) * 3 + c])));
  INFO("largest |decoded - written| = " << worst);
  CHECK(worst <= 3);
}

TEST_CASE("PNG: 8 and 16-bit grey and RGB, interlaced or not, exactly — gAMA and sRGB reported only", "[image]") {
  for (int bits : {8, 16})
    for (int channels : {1, 3})
      for (bool interlace : {false, true}) {
        INFO(bits << "-bit, " << channels << " channel(s), interlaced " << interlace);
        const TestImage im = random_image(29, 19, channels, bits, 5u * bits + channels + interlace);
        test::PngWriteOptions o;
        o.interlace = interlace;
        o.gamma = 0.45455;
        o.srgb = true;
        const auto file = test::write_png(im, o);
        CHECK(detect_format(file.data(), file.size()) == FileFormat::Png);
        const RawImage img = decode_any(file);
        check_meta(img, "png", bits, channels);
        CHECK(img.meta.declared_colour == "sRGB;gamma 0.45455");
        require_exact(img, im);
      }
}

TEST_CASE("JPEG: 8-bit grey and RGB within the quantisation of quality 100 4:4:4 — every coding", "[image]") {
  // A smooth image: at quality 100 (all quantisers 1) the error is the DCT's and YCbCr's rounding
  // (measured: at most 2 levels grey, 4 RGB).
  for (int channels : {1, 3}) {
    const TestImage im = test::make_image(64, 40, channels, 8, [](int x, int y, int c) {
      return static_cast<int>(128 + 90 * std::sin(0.07 * x + 0.05 * y + c));
    });
    struct Case {
      const char* name;
      test::JpegWriteOptions o;
    };
    test::JpegWriteOptions base;
    base.quality = 100;
    std::vector<Case> cases{{"baseline", base}};
    test::JpegWriteOptions p = base;
    p.progressive = true;
    cases.push_back({"progressive", p});
    test::JpegWriteOptions a = base;
    a.arithmetic = true;
    cases.push_back({"arithmetic", a});
    if (channels == 3) {
      test::JpegWriteOptions r = base;
      r.rgb = true;
      cases.push_back({"RGB without YCbCr", r});
    }
    for (const auto& c : cases) {
      INFO(c.name << ", " << channels << " channel(s)");
      const auto file = test::write_jpeg(im, c.o);
      CHECK(detect_format(file.data(), file.size()) == FileFormat::Jpeg);
      const RawImage img = decode_any(file);
      check_meta(img, "jpeg", 8, channels);
      double worst = 0;
      for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
          for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(img.at(x, y, k) - double(im.samples[(y * im.width + x) * channels +
                                                                                  (channels == 1 ? 0 : k)])));
      INFO("largest |decoded - written| = " << worst);
      CHECK(worst <= (channels == 1 ? 2 : 4));  // RGB: plus YCbCr's rounding both ways
    }
  }
}

TEST_CASE("JPEG: an ICC profile is reported, not applied", "[image]") {
  const TestImage im = test::make_image(16, 16, 3, 8, [](int, int, int c) { return 60 + 50 * c; });
  test::JpegWriteOptions o;
  o.quality = 100;
  o.icc = std::vector<std::uint8_t>(70000, 3);  // spans two APP2 markers
  const RawImage img = decode_jpeg(test::write_jpeg(im, o).data(), test::write_jpeg(im, o).size());
  CHECK(img.meta.declared_colour == "ICC profile (70000 bytes)");
  CHECK(std::abs(img.at(5, 5, 2) - 160.0f) <= 1.0f);
}

TEST_CASE("decodes are identical natively and in wasm (golden hashes)", "[image]") {
  // The real chart JPEG (tests/data/passport; libjpeg-turbo's SIMD IDCT natively, plain C in wasm).
  const RawImage jpeg = decode_any(bytes_of(test::read_test_file(kJpeg)));
  CHECK(jpeg.meta.format == "jpeg");
  INFO("the chart JPEG: " << jpeg.width << " x " << jpeg.height);
  CHECK(hash_hex(linear_data_hash(jpeg)) == "f627301c32fffcff");
  // A 4:2:0 progressive JPEG written here (encoder and decoder both in the comparison).
  const TestImage im = test::make_image(61, 45, 3, 8, [](int x, int y, int c) { return (x * 7 + y * 3 + c * 50) % 256; });
  test::JpegWriteOptions o;
  o.quality = 80;
  o.subsample = true;
  o.progressive = true;
  const RawImage written = decode_any(test::write_jpeg(im, o));
  CHECK(hash_hex(linear_data_hash(written)) == "30aee09904bb100a");
}

TEST_CASE("a chart in an 8-bit TIFF is sampled to its planted patch means", "[image]") {
  std::vector<std::array<std::uint16_t, 3>> colours;
  for (int i = 0; i < 24; ++i)
    colours.push_back({static_cast<std::uint16_t>(20 + 9 * i), static_cast<std::uint16_t>(230 - 8 * i),
                       static_cast<std::uint16_t>(60 + 5 * i)});
  colours[18] = {255, 255, 255};  // clipped white
  colours[23] = {0, 0, 0};        // black: "dark"
  const auto chart = test::render_chart("cc24", 360, 260, 17, 23, 320, 214, colours, {128, 128, 128}, 8);
  const RawImage img = decode_any(test::write_tiff(chart.image));
  LayoutOptions lo;
  lo.chart = "cc24";
  const ChartSample s = sample_chart(img, lo, chart.corners);
  REQUIRE(s.patches.size() == 24);
  for (int i = 0; i < 24; ++i) {
    const PatchSample& p = s.patches[i];
    INFO("patch " << p.id);
    for (int c = 0; c < 3; ++c) {
      CHECK(p.mean[c] == colours[i][c]);
      CHECK(p.std[c] == 0.0);
    }
    CHECK(p.n > 300);
    const bool sat = std::find(p.flags.begin(), p.flags.end(), "saturated") != p.flags.end();
    const bool dark = std::find(p.flags.begin(), p.flags.end(), "dark") != p.flags.end();
    CHECK(sat == (i == 18));
    CHECK(dark == (i == 23));
  }
  CHECK(s.patches[18].saturated_fraction[1] == 1.0);
  // The same chart through 16-bit PNG: values x 257, same means.
  auto chart16 = chart;
  chart16.image.bits = 16;
  for (auto& v : chart16.image.samples) v = static_cast<std::uint16_t>(v * 257);
  const ChartSample s16 = sample_chart(decode_any(test::write_png(chart16.image)), lo, chart.corners);
  for (int i = 0; i < 24; ++i) CHECK(s16.patches[i].mean[0] == colours[i][0] * 257.0);
}

TEST_CASE("the preview of an image shows its stored values", "[image]") {
  const TestImage im = test::make_image(40, 30, 3, 16, [](int x, int, int c) { return x < 20 ? 257 * (10 + c) : 65535; });
  const Preview pv = render_preview(decode_any(test::write_png(im)), 20);
  REQUIRE(pv.scale == 2);
  CHECK(int(pv.rgba[0]) == 10);
  CHECK(int(pv.rgba[1]) == 11);
  CHECK(int(pv.rgba[2]) == 12);
  CHECK(int(pv.rgba[(19) * 4]) == 255);
}

TEST_CASE("the format comes from the bytes, not the name: RAW, image, other image, garbage", "[image]") {
  const auto jpeg = bytes_of(test::read_test_file(kJpeg));
  CHECK(detect_format(jpeg.data(), jpeg.size()) == FileFormat::Jpeg);  // the same bytes as "x.CR2"
  const auto dng = bytes_of(test::read_test_file(kPassport));
  CHECK(detect_format(dng.data(), dng.size()) == FileFormat::Raw);  // TIFF-structured, DNGVersion
  const auto cr2 = bytes_of(test::read_test_file(kCr2));
  CHECK(detect_format(cr2.data(), cr2.size()) == FileFormat::Raw);  // TIFF-structured, "CR"
  const auto kdc = bytes_of(test::read_test_file(kKdc));
  CHECK(detect_format(kdc.data(), kdc.size()) == FileFormat::Raw);  // TIFF-structured, LibRaw's
  CHECK(decode_any(dng).meta.format == "raw");
  CHECK(decode_any(dng).meta.encoding == "linear");

  require_code([] { decode_any(std::vector<std::uint8_t>{}); }, ErrorCode::EmptyFile);
  for (const char* sig : {"GIF89a", "BM\x36\x10\x0e\0\0\0\0\0\x36\0\0\0", "RIFF\x10\0\0\0WEBPVP8 ",
                          "\0\0\0\x18" "ftypheic\0\0\0\0", "P6\n", "8BPS\0\x01"}) {
    std::vector<std::uint8_t> b(sig, sig + 16);
    b.resize(400, 0x55);
    INFO(sig);
    require_code([&] { decode_any(b); }, ErrorCode::ImageUnsupported);
  }
  // Random bytes and text stay RAW refusals, saying what else was tried.
  std::mt19937 rng(42);
  std::vector<std::uint8_t> random(100000);
  for (auto& v : random) v = static_cast<std::uint8_t>(rng() >> 24);
  require_code([&] { decode_any(random); }, ErrorCode::RawUnsupported);
  // RAW-looking garbage: a CR2's first 4 KiB then noise goes to LibRaw and gets a RAW code.
  std::vector<std::uint8_t> fake(cr2.begin(), cr2.begin() + 4096);
  fake.resize(200000);
  for (std::size_t i = 4096; i < fake.size(); ++i) fake[i] = static_cast<std::uint8_t>(rng() >> 24);
  const ErrorCode fake_code = test::code_of([&] { decode_any(fake); });
  INFO(error_code_name(fake_code));
  CHECK((fake_code == ErrorCode::RawCorrupt || fake_code == ErrorCode::RawTruncated ||
         fake_code == ErrorCode::RawUnsupported));
  // A TIFF header then noise: no RAW, so libtiff, which finds no directory.
  std::vector<std::uint8_t> tiff_noise(random);
  std::memcpy(tiff_noise.data(), "II*\0\x08\0\0\0", 8);
  require_code([&] { decode_any(tiff_noise); }, ErrorCode::ImageCorrupt);
}

TEST_CASE("unsupported image variants are refused with IMAGE_UNSUPPORTED", "[image]") {
  const TestImage rgba = random_image(16, 8, 4, 8, 1);
  const TestImage rgb = random_image(16, 8, 3, 8, 2);
  const TestImage grey = random_image(16, 8, 1, 8, 3);
  SECTION("TIFF") {
    // `im` written as a TIFF with the options `set` gives; the decoder must refuse it as unsupported.
    const auto require_unsupported_tiff = [](const TestImage& im, const std::function<void(test::TiffWriteOptions&)>& set) {
      test::TiffWriteOptions o;
      set(o);
      require_code([&] { decode_any(test::write_tiff(im, o)); }, ErrorCode::ImageUnsupported);
    };
    const auto as_is = [](test::TiffWriteOptions&) {};
    require_unsupported_tiff(rgba, [](auto& o) { o.extra_samples = 1; });  // RGB + alpha
    require_unsupported_tiff(rgba, as_is);                                 // CMYK
    require_unsupported_tiff(grey, [](auto& o) { o.photometric = 3; });    // palette
    require_unsupported_tiff(grey, [](auto& o) { o.photometric = 0; });    // min-is-white
    for (int bits : {1, 4, 12, 32}) {
      INFO(bits << "-bit");
      TestImage odd = grey;
      odd.bits = bits;
      require_unsupported_tiff(odd, as_is);
    }
    TestImage f32 = grey;
    f32.bits = 32;
    require_unsupported_tiff(f32, [](auto& o) { o.sample_format = 3; });   // float
    require_unsupported_tiff(grey, [](auto& o) { o.sample_format = 2; });  // signed integer
    // Codecs outside the read set (the same natively and in wasm): LZMA, ZSTD, CCITT, old JPEG.
    for (std::uint16_t comp : {34925, 50000, 4, 6}) {
      INFO("compression " << comp);
      require_code([&] { decode_any(tiff_with_short(test::write_tiff(grey), 259, comp)); }, ErrorCode::ImageUnsupported);
    }
  }
  SECTION("PNG") {
    test::PngWriteOptions pal;
    pal.palette = true;
    require_code([&] { decode_any(test::write_png(test::make_image(8, 8, 3, 8, [](int x, int, int c) { return x * 30 + c; }), pal)); },
                 ErrorCode::ImageUnsupported);
    require_code([&] { decode_any(test::write_png(rgba)); }, ErrorCode::ImageUnsupported);
    require_code([&] { decode_any(test::write_png(random_image(8, 8, 2, 16, 4))); }, ErrorCode::ImageUnsupported);
    test::PngWriteOptions four;
    four.grey_bits = 4;
    require_code([&] { decode_any(test::write_png(test::make_image(8, 8, 1, 8, [](int x, int, int) { return x; }), four)); },
                 ErrorCode::ImageUnsupported);
  }
  SECTION("JPEG") {
    test::JpegWriteOptions cmyk;
    cmyk.cmyk = true;
    require_code([&] { decode_any(test::write_jpeg(rgba, cmyk)); }, ErrorCode::ImageUnsupported);
    auto twelve = test::write_jpeg(rgb);
    twelve[jpeg_sof(twelve) + 2] = 12;  // sample precision
    require_code([&] { decode_any(twelve); }, ErrorCode::ImageUnsupported);
    auto lossless = test::write_jpeg(rgb);
    lossless[jpeg_sof(lossless) - 1] = 0xC3;  // SOF3: lossless
    require_code([&] { decode_any(lossless); }, ErrorCode::ImageUnsupported);
  }
}

TEST_CASE("truncated and corrupt images give IMAGE_CORRUPT, oversized ones LIMIT_EXCEEDED", "[image]") {
  const TestImage im = random_image(64, 48, 3, 8, 9);
  const auto cut = [](std::vector<std::uint8_t> b, double keep) {
    b.resize(static_cast<std::size_t>(b.size() * keep));
    return b;
  };
  // The file cut to each fraction `keep` of its bytes is refused as corrupt.
  const auto require_corrupt_when_cut = [&](const std::vector<std::uint8_t>& file, std::initializer_list<double> keeps) {
    for (double keep : keeps) {
      INFO("keep " << keep);
      require_code([&] { decode_any(cut(file, keep)); }, ErrorCode::ImageCorrupt);
    }
  };
  SECTION("TIFF") {
    test::TiffWriteOptions o;
    o.compression = 8;
    o.rows_per_strip = 8;
    const auto file = test::write_tiff(im, o);
    // libtiff writes the directory after the strips: a cut file has lost its directory.
    require_corrupt_when_cut(file, {0.5});
    auto bad = file;
    for (std::size_t i = 16; i < 200; ++i) bad[i] ^= 0x5A;  // inside the first Deflate strip
    require_code([&] { decode_any(bad); }, ErrorCode::ImageCorrupt);
  }
  SECTION("PNG") {
    const auto file = test::write_png(im);
    require_corrupt_when_cut(file, {0.3, 0.9, 0.999});
    auto flipped = file;
    flipped[flipped.size() / 2] ^= 0x01;  // IDAT CRC no longer matches
    require_code([&] { decode_any(flipped); }, ErrorCode::ImageCorrupt);
    require_code([&] { decode_any(png_claiming(file, 100000, 100000)); }, ErrorCode::LimitExceeded);
    require_code([&] { decode_any(png_claiming(file, 0, 48)); }, ErrorCode::ImageCorrupt);
  }
  SECTION("JPEG") {
    const auto file = test::write_jpeg(im);
    require_corrupt_when_cut(file, {0.05, 0.5, 0.95});
    auto big = file;
    const std::size_t sof = jpeg_sof(big);
    big[sof + 3] = 0xEA;  // height 60000
    big[sof + 4] = 0x60;
    big[sof + 5] = 0xEA;  // width 60000
    big[sof + 6] = 0x60;
    require_code([&] { decode_any(big); }, ErrorCode::LimitExceeded);
  }
  SECTION("any format: the megapixel limit applies before decoding") {
    ImageDecodeOptions small;
    small.max_megapixels = 0.003;  // 64 x 48 = 0.003072 MP
    require_code([&] { decode_any(test::write_tiff(im), {}, small); }, ErrorCode::LimitExceeded);
    require_code([&] { decode_any(test::write_png(im), {}, small); }, ErrorCode::LimitExceeded);
    require_code([&] { decode_any(test::write_jpeg(im), {}, small); }, ErrorCode::LimitExceeded);
  }
}

TEST_CASE("a plain grey or RGB TIFF from a camera maker is a TIFF, not sensor data", "[image]") {
  for (int channels : {1, 3})
    for (int bits : {8, 16}) {
      INFO(channels << " channel(s), " << bits << "-bit");
      const TestImage im = random_image(64, 48, channels, bits, 77);
      test::TiffWriteOptions o;
      o.make = "Canon";
      o.model = "Canon EOS 550D";
      const auto file = test::write_tiff(im, o);
      CHECK(detect_format(file.data(), file.size()) == FileFormat::Tiff);
      const RawImage img = decode_any(file);
      CHECK(img.meta.make == "Canon");
      require_exact(img, im);
    }
}

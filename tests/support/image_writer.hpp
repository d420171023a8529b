// tristim — TIFF, PNG and JPEG files written in memory at test time with the same libraries the
// decoders use (libtiff, libpng, libjpeg-turbo), for planted-value tests of capture/image.hpp,
// its bad-input codes, and the fuzz seeds. Test-only code: writer failures throw
// std::runtime_error.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tristim::test {

/// Pixels to write: width × height × channels samples, interleaved, row-major, each < 2^bits.
struct TestImage {
  int width = 0, height = 0;
  int channels = 3;  ///< 1 grey, 3 RGB, 2 grey+alpha, 4 RGBA or CMYK (for refusals)
  int bits = 8;      ///< 8 or 16 (TIFF also 1, 4, 12, 32 for refusals: samples then unused)
  std::vector<std::uint16_t> samples;
  std::uint16_t& at(int x, int y, int c) { return samples[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
};

/// An image with every sample set by f(x, y, c).
template <class F>
TestImage make_image(int width, int height, int channels, int bits, F f) {
  TestImage im{width, height, channels, bits, {}};
  im.samples.resize(static_cast<std::size_t>(width) * height * channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) im.at(x, y, c) = static_cast<std::uint16_t>(f(x, y, c));
  return im;
}

struct TiffWriteOptions {
  /// libtiff COMPRESSION_* (1 none, 5 LZW, 8 Deflate, 32773 PackBits, 7 JPEG, 34925 LZMA …).
  int compression = 1;
  int predictor = 1;            ///< 2: horizontal differencing (with LZW/Deflate)
  bool planar_separate = false;
  int tile = 0;                 ///< tile side (multiple of 16); 0: strips
  int rows_per_strip = 0;       ///< 0: libtiff's default
  bool big_endian = false;
  bool big_tiff = false;
  int photometric = -1;         ///< -1: grey or RGB from channels; else written as given
  int extra_samples = 0;        ///< number of ExtraSamples (unassociated alpha) to declare
  int sample_format = 1;        ///< 1 uint, 2 int, 3 IEEE float
  int orientation = 0;          ///< 0: no tag
  int jpeg_quality = 90;
  bool jpeg_ycbcr = false;      ///< JPEG compression with YCbCr photometric (colour mode RGB)
  std::string make, model, datetime;  ///< written when not empty
  std::vector<std::uint8_t> icc;      ///< ICCProfile tag when not empty
};
std::vector<std::uint8_t> write_tiff(const TestImage& image, const TiffWriteOptions& options = {});

struct PngWriteOptions {
  bool interlace = false;       ///< Adam7
  bool palette = false;         ///< write 8-bit RGB as palette (indexed) colour, ≤ 256 colours
  double gamma = 0;             ///< gAMA chunk when > 0
  bool srgb = false;            ///< sRGB chunk
  int grey_bits = 0;            ///< 1, 2 or 4: low-depth grey (samples must fit)
};
std::vector<std::uint8_t> write_png(const TestImage& image, const PngWriteOptions& options = {});

struct JpegWriteOptions {
  int quality = 95;
  bool subsample = false;       ///< 4:2:0 chroma (default 4:4:4)
  bool progressive = false;
  bool arithmetic = false;
  bool rgb = false;             ///< store RGB without the YCbCr transform (Adobe marker)
  bool cmyk = false;            ///< 4 channels written as CMYK
  std::vector<std::uint8_t> icc;
};
std::vector<std::uint8_t> write_jpeg(const TestImage& image, const JpegWriteOptions& options = {});

/// A chart seen head-on: an RGB image of `width` × `height` whose patch grid (chart/layout.hpp
/// layout `chart`) spans the pixel rectangle [x0, x0 + w) × [y0, y0 + h); a pixel whose centre
/// falls in patch i gets colours[i] (stored units, one per patch in layout order), every other
/// pixel `background`. `corners` are the grid's corners for sample_chart.
struct RenderedChart {
  TestImage image;
  std::array<double, 8> corners{};
};
RenderedChart render_chart(const std::string& chart, int width, int height, int x0, int y0, int w, int h,
                           const std::vector<std::array<std::uint16_t, 3>>& colours,
                           std::array<std::uint16_t, 3> background, int bits);

}  // namespace tristim::test

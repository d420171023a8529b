// tristim — a minimal DNG writer (uncompressed 16-bit CFA, 2×2 or 6×6): the colorimetry lab's
// rendered chart photographs (lab/render.hpp), and the tests' planted-value RAW files, synthetic
// benchmark files and headers with absurd sizes.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tristim {

struct DngWriteOptions {
  std::string make = "tristim", model = "Synthetic CFA";
  /// CFA, row-major: 4 letters (2×2) or 36 (6×6, e.g. X-Trans); R, G, B (C, M, Y for tests of
  /// 4-colour sensors).
  std::string cfa = "RGGB";
  std::uint16_t black = 0;           ///< BlackLevel (one value)
  std::uint16_t white = 65535;       ///< WhiteLevel
  /// ColorMatrix1 (XYZ -> camera, row-major); default: a plausible daylight matrix.
  std::array<double, 9> color_matrix{0.6461, -0.0907, -0.0882, -0.4300, 1.2184, 0.2378,
                                     -0.0819, 0.1944, 0.5931};
  std::array<double, 3> as_shot_neutral{0.5, 1.0, 0.7};
  double exposure_s = 0;             ///< ExposureTime (33434), written when > 0
  double f_number = 0;               ///< FNumber (33437), written when > 0
  std::uint16_t iso = 0;             ///< ISOSpeedRatings (34855), written when > 0 in an EXIF
                                     ///< sub-IFD (34665): LibRaw reads ISO only from there
  std::uint32_t header_width = 0;    ///< if nonzero, the header claims this width (tests)
  std::uint32_t header_height = 0;   ///< if nonzero, the header claims this height (tests)
};

/// A little-endian DNG 1.4 with one uncompressed 16-bit CFA strip of width×height sensor
/// values (row-major). Throws Error(InvalidArgument) if sizes do not match or the CFA is bad.
std::vector<std::uint8_t> write_dng(const std::vector<std::uint16_t>& cfa_values, int width,
                                    int height, const DngWriteOptions& options = {});

/// A little-endian baseline TIFF, RGB, 16 bits per sample, one uncompressed strip of width×height
/// interleaved R, G, B values (row-major). Throws Error(InvalidArgument) if sizes do not match.
std::vector<std::uint8_t> write_tiff_rgb16(const std::vector<std::uint16_t>& rgb, int width, int height);

}  // namespace tristim

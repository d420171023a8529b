// tristim — RAW decoding (LibRaw) to linear camera RGB for measurement.
//
// Only core/src/raw.cpp includes libraw.h. What decode_raw returns is what the sensor recorded,
// minus the black level: no white balance, no gamma, no colour matrix, no auto-brightness, no
// demosaicing interpolation.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/io/fields.hpp"

namespace tristim {

/// How sensor pixels were combined into one measurement pixel (RawMetadata::layout).
///  - "bayer":  2×2 CFA block -> R, G = mean of the two greens, B (half resolution).
///  - "xtrans": Fujifilm X-Trans 6×6 CFA; each 3×3 block holds 2 R, 5 G, 2 B sensor pixels and
///              becomes one pixel with the mean of each colour (third resolution, no interpolation).
///  - "linear": already-RGB data (linear DNG, sRAW): one sensor pixel -> one pixel (block 1×1).
///  - "monochrome": one channel; copied to R = G = B (block 1×1).
///  - "rgb": a TIFF/PNG/JPEG image with three samples per pixel (capture/image.hpp; block 1×1).
/// Anything else (4-colour CMYG / RGBE CFAs, CFAs whose 2×2 block lacks R, G or B, Foveon,
/// floating-point DNG) is refused with ErrorCode::RawUnsupported naming the pattern.
struct RawMetadata {
  std::string format = "raw";        ///< the decoder: "raw" (LibRaw), "tiff", "png", "jpeg"
  std::string encoding = "linear";   ///< "linear": black-subtracted sensor DN (RAW); "stored":
                                     ///< an image's values as stored in the file, 0..white_level,
                                     ///< possibly non-linear (see capture/image.hpp)
  std::string declared_colour;       ///< images: what the file declares about its colour encoding,
                                     ///< reported and NEVER applied, ';'-separated, e.g.
                                     ///< "ICC profile (3144 bytes);gamma 0.45455"; "" if nothing
  std::string make, model, lens;     ///< "" when unknown
  double iso = 0;                    ///< ISO speed, 0 if unknown
  double shutter_s = 0;              ///< exposure time in seconds, 0 if unknown
  double f_number = 0;               ///< aperture f-number, 0 if unknown
  std::int64_t timestamp = 0;        ///< seconds since 1970 as LibRaw reports it (camera clock)
  std::string timestamp_iso;         ///< the same as "YYYY-MM-DDTHH:MM:SS" (camera clock, no zone)
  std::string layout;                ///< "bayer", "xtrans", "linear", "monochrome" (see above)
  std::string cfa_pattern;           ///< row-major colours from the image's top-left: "RGGB";
                                     ///< 36 letters for X-Trans; "" for linear/monochrome
  int cfa_width = 0, cfa_height = 0; ///< size of the CFA repeat (2×2, 6×6, 0 for none)
  int block = 1;                     ///< sensor pixels per measurement pixel side (2, 3 or 1)
  int sensor_width = 0, sensor_height = 0;  ///< visible sensor area used, in sensor pixels
  int raw_width = 0, raw_height = 0;        ///< full stored raster incl. masked borders
  int width = 0, height = 0;         ///< the measurement image (half resolution for Bayer)
  int bits = 0;                      ///< bits per sample LibRaw reports (0 if unknown); images: 8 or 16
  int flip = 0;                      ///< LibRaw's orientation: 0 none, 3 180°, 5 90° CCW, 6 90° CW.
                                     ///< The measurement image and preview stay in sensor orientation.
  std::array<double, 4> cfa_black{}; ///< black level per 2×2 CFA position (row-major), DN
  std::array<double, 3> black_level{};  ///< mean black level subtracted from R, G, B, DN
  double white_level = 0;            ///< raw saturation level (LibRaw `maximum`), DN incl. black
  std::array<double, 3> saturation{};   ///< white_level - black per channel: the clip level of
                                        ///< the linear image's R, G, B values
  std::array<double, 9> rgb_cam{};   ///< LibRaw camera RGB -> linear sRGB (row-major, preview only)
  std::array<double, 9> cam_xyz{};   ///< LibRaw XYZ(D65) -> camera RGB (row-major, preview only)
  std::array<double, 3> as_shot_wb{};   ///< camera's as-shot multipliers, G = 1 (preview only)
  std::array<double, 3> daylight_wb{};  ///< LibRaw's daylight multipliers, G = 1 (preview only)
  std::string decoder;               ///< LibRaw's unpack function name, for diagnostics
};

/// Limits and thresholds for decode_raw.
struct DecodeOptions {
  /// Refuse (RawTooLarge) files whose sensor raster exceeds this many pixels. 160 MP keeps the
  /// worst case (raw raster + float RGB) well inside a 2 GiB wasm heap.
  double max_megapixels = 160.0;
  /// A sensor pixel is saturated when raw - black >= saturation_fraction * (white - black).
  double saturation_fraction = 0.98;
};

/// Linear camera RGB of one RAW file, ready for measurement.
struct RawImage {
  RawMetadata meta;
  int width = 0, height = 0;
  /// width*height*3 floats, row-major, interleaved R, G, B: mean of the block's sensor values of
  /// each colour minus the black level, in raw DN (not clipped at 0: noise averages stay unbiased).
  std::vector<float> rgb;
  /// width*height bytes: bit 0/1/2 set when any R/G/B sensor pixel of the block is saturated
  /// (see DecodeOptions::saturation_fraction). Never cleared by calibration.
  std::vector<std::uint8_t> saturated;

  float at(int x, int y, int c) const { return rgb[(static_cast<size_t>(y) * width + x) * 3 + c]; }
};

/// Decodes a RAW file held in memory (LibRaw open_buffer; no filesystem needed).
/// Errors: EmptyFile (0 bytes), RawUnsupported (not a RAW LibRaw knows, or an unsupported
/// sensor layout), RawTruncated (data ends early), RawCorrupt (inconsistent header or data),
/// RawTooLarge (over DecodeOptions::max_megapixels or LibRaw's memory limit).
RawImage decode_raw(const std::uint8_t* data, std::size_t size, const DecodeOptions& options = {});
inline RawImage decode_raw(const std::vector<std::uint8_t>& bytes, const DecodeOptions& options = {}) {
  return decode_raw(bytes.data(), bytes.size(), options);
}

/// True when LibRaw's open_buffer accepts the bytes as a camera RAW (its file-type
/// identification; no image data is unpacked, no error is thrown), with the raster it would read
/// (raw_width × raw_height, when the pointers are given). capture/image.hpp uses it to tell
/// TIFF-structured RAWs from plain TIFFs.
bool libraw_identifies(const std::uint8_t* data, std::size_t size, int* raw_width = nullptr,
                       int* raw_height = nullptr);

/// Metadata only (no unpacking of image data), for `tristim inspect`.
RawMetadata inspect_raw(const std::uint8_t* data, std::size_t size, const DecodeOptions& options = {});

/// Metadata as a JSON object (stable field names = the struct's).
std::string metadata_to_json(const RawMetadata& meta);

/// A display preview — NEVER used for measurement. The linear image is box-downsampled by an
/// integer factor `scale` so that max(width, height) <= max_side, white balanced with the
/// as-shot multipliers, converted with LibRaw's camera matrix (rgb_cam), exposed so that the
/// 99th percentile of luminance maps to 0.9, and encoded with the sRGB transfer curve.
/// An image with stored values (meta.encoding "stored": TIFF/PNG/JPEG) is shown as stored:
/// box mean / white_level × 255, nothing else.
/// Preview pixel (i, j) covers measurement pixels [i*scale, (i+1)*scale) × [j*scale, (j+1)*scale).
struct Preview {
  int width = 0, height = 0;
  int scale = 1;                    ///< measurement pixels per preview pixel (each axis)
  std::vector<std::uint8_t> rgba;   ///< width*height*4, alpha 255
};
Preview render_preview(const RawImage& image, int max_side);

/// FNV-1a 64-bit hash of width, height and the bit patterns of every rgb float: equal hashes
/// mean identical linear data (used to compare native and wasm decodes).
std::uint64_t linear_data_hash(const RawImage& image);
std::string hash_hex(std::uint64_t hash);

}  // namespace tristim

// The metadata's field list (defined in raw.cpp): `tristim inspect`'s JSON and the wasm binding
// (RawImage.metadata()) use it.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(RawMetadata);
}  // namespace tristim::fields

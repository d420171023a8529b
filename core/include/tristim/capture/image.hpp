// tristim — non-RAW images in: 8/16-bit TIFF, 8/16-bit PNG and JPEG, decoded by Debian's libtiff,
// libpng and libjpeg-turbo to the same RawImage the RAW decoder returns, so that chart sampling,
// calibration frames, the CLI and the page take either.
//
// The values are the file's values AS STORED: no colour management, no gamma, no ICC profile,
// no white balance, no black subtraction, no rotation. What the file declares about its colour
// encoding (an ICC profile, a PNG sRGB/gAMA chunk, a TIFF transfer function) is reported in
// RawMetadata::declared_colour and never applied: turning stored values into linear ones is the
// linearisation stage's job (linearisation/linearisation.hpp), which reads the encoding from
//   meta.format     "tiff", "png" or "jpeg" (RAW files: "raw")
//   meta.encoding   "stored" (RAW files: "linear")
//   meta.bits       8 or 16: bits per stored sample
//   meta.white_level = meta.saturation[c] = the full scale, 2^bits - 1 (255 or 65535)
//   meta.black_level = {0, 0, 0}
// RawImage::rgb holds the stored values as floats (exact: every 16-bit integer is a float);
// a grey image (meta.layout "monochrome") is copied to R = G = B, an RGB one has layout "rgb".
// A sample is saturated (RawImage::saturated) when it equals the full scale: a stored value
// carries no headroom, so only the top code is known to be clipped.
//
// Which decoder runs is decided by the file's first bytes, never by its name (a JPEG renamed
// .CR2 is decoded as a JPEG): see detect_format.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/capture/raw.hpp"

namespace tristim {

enum class FileFormat {
  Raw,   ///< anything LibRaw reads (also every file that is none of the below: LibRaw decides)
  Tiff,  ///< a TIFF that is not a camera RAW (TIFF-structured RAWs — DNG, CR2, NEF, ARW … — are Raw)
  Png,
  Jpeg,
};

/// "raw", "tiff", "png", "jpeg".
const char* file_format_name(FileFormat format);

/// The decoder for these bytes, from their signature:
///   PNG   89 50 4E 47 0D 0A 1A 0A;   JPEG  FF D8 FF;
///   TIFF  "II*\0" / "MM\0*" (and BigTIFF "II+\0" / "MM\0+"), unless it is a camera RAW: a CR2
///         marker ("CR" at byte 8), a DNGVersion tag in the first directory, or a TIFF LibRaw
///         identifies as a RAW — except when the first directory declares a grey or RGB image,
///         has no SubIFDs, and is the raster LibRaw would read (LibRaw takes a 16-bit grey TIFF
///         with a camera maker's Make tag for sensor data; such a file is a TIFF here);
///   other image formats that are not read here (GIF, BMP, WebP, HEIF/AVIF, JPEG 2000, JPEG XL,
///   PNM, OpenEXR, Radiance HDR, PSD): ErrorCode::ImageUnsupported naming the format;
///   anything else: Raw. Errors: EmptyFile (0 bytes), ImageUnsupported.
FileFormat detect_format(const std::uint8_t* data, std::size_t size);

/// Options of the image decoders (the RAW decoder keeps its own DecodeOptions).
struct ImageDecodeOptions {
  /// Refuse (LimitExceeded) images of more pixels than this, before any pixel is decoded.
  /// 64 MP: the decoded float RGB (12 bytes per pixel) plus the decoders' own buffers stays
  /// well inside a 2 GiB wasm heap.
  double max_megapixels = 64.0;
};

/// Baseline TIFF: 1 sample (grey, min-is-black) or 3 (RGB, or YCbCr in a JPEG-compressed TIFF,
/// which libjpeg-turbo returns as RGB) of 8 or 16 unsigned bits, contiguous or planar, strips
/// or tiles, uncompressed, LZW, PackBits, Deflate or JPEG; the first image of the file.
/// Refused with ImageUnsupported (naming the variant): alpha or other extra samples, palette,
/// CMYK, CIELab, min-is-white, 1/2/4/12/32-bit, signed or floating-point samples, and any other
/// compression (CCITT, old-style JPEG, LZMA, ZSTD, WebP, JBIG, LERC …: the same set is read
/// natively and in wasm). Truncated or inconsistent data: ImageCorrupt. Make/Model/DateTime and
/// Orientation (as meta.flip, LibRaw's convention) are read from the TIFF's own tags.
RawImage decode_tiff(const std::uint8_t* data, std::size_t size, const ImageDecodeOptions& options = {});

/// PNG: grey or RGB, 8 or 16 bits, interlaced or not. Refused (ImageUnsupported): palette,
/// grey+alpha, RGBA, 1/2/4-bit grey. The tRNS chunk is ignored (values as stored). Any read error
/// — truncation, a bad CRC in a critical chunk, a bad zlib stream, a missing IEND — ImageCorrupt.
RawImage decode_png(const std::uint8_t* data, std::size_t size, const ImageDecodeOptions& options = {});

/// JPEG (baseline, extended or progressive, 8-bit, Huffman or arithmetic coded): 1 component
/// (grey) or 3 (YCbCr or RGB, returned as RGB by libjpeg-turbo's accurate integer IDCT and
/// upsampling, identical natively and in wasm). Refused (ImageUnsupported): CMYK/YCCK (4
/// components), 12-bit and lossless JPEG. Truncated or corrupt entropy data (libjpeg's
/// "premature end", "corrupt data" warnings, which it would otherwise paper over with grey):
/// ImageCorrupt. More than 1000 progressive scans: LimitExceeded.
RawImage decode_jpeg(const std::uint8_t* data, std::size_t size, const ImageDecodeOptions& options = {});

/// The one entry point of the CLI and the page: detect_format, then decode_raw (with
/// `raw_options`) or the image decoder (with `image_options`). Errors: those of detect_format
/// and of the decoder chosen; a RAW decoder refusal of an unrecognised file says that the file
/// is no RAW, TIFF, PNG or JPEG (RawUnsupported).
RawImage decode_any(const std::uint8_t* data, std::size_t size, const DecodeOptions& raw_options = {},
                    const ImageDecodeOptions& image_options = {});
inline RawImage decode_any(const std::vector<std::uint8_t>& bytes, const DecodeOptions& raw_options = {},
                           const ImageDecodeOptions& image_options = {}) {
  return decode_any(bytes.data(), bytes.size(), raw_options, image_options);
}

}  // namespace tristim

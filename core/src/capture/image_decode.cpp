// Images in: the format from the first bytes, the one decode entry point (decode_any), and what
// the TIFF / PNG / JPEG decoders share (image_common.hpp).
#include <cstring>
#include <sstream>

#include "image_common.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace image_detail {

RawImage new_image_header(const char* format, std::uint64_t width, std::uint64_t height, int channels,
                          int bits, const ImageDecodeOptions& options) {
  if (width == 0 || height == 0)
    throw Error(ErrorCode::ImageCorrupt, std::string("the ") + format + " header gives a zero image size (" +
                                             std::to_string(width) + " x " + std::to_string(height) + ")");
  const double mp = static_cast<double>(width) * static_cast<double>(height) / 1e6;
  if (mp > options.max_megapixels) {
    std::ostringstream ss;
    ss << "the " << format << " image is " << width << " x " << height << " pixels (" << mp
       << " MP), over the limit of " << options.max_megapixels << " MP";
    throw Error(ErrorCode::LimitExceeded, ss.str());
  }
  RawImage img;
  img.width = static_cast<int>(width);
  img.height = static_cast<int>(height);
  RawMetadata& m = img.meta;
  m.format = format;
  m.encoding = "stored";
  m.layout = channels == 1 ? "monochrome" : "rgb";
  m.block = 1;
  m.sensor_width = m.raw_width = m.width = img.width;
  m.sensor_height = m.raw_height = m.height = img.height;
  m.bits = bits;
  m.white_level = bits == 16 ? 65535.0 : 255.0;
  m.saturation = {m.white_level, m.white_level, m.white_level};
  m.as_shot_wb = m.daylight_wb = {1.0, 1.0, 1.0};
  m.decoder = format;
  return img;
}

void allocate_pixels(RawImage& img) {
  const std::size_t n = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height);
  img.rgb.assign(n * 3, 0.0f);
  img.saturated.assign(n, 0);
}

RawImage new_image(const char* format, std::uint64_t width, std::uint64_t height, int channels,
                   int bits, const ImageDecodeOptions& options) {
  RawImage img = new_image_header(format, width, height, channels, bits, options);
  allocate_pixels(img);
  return img;
}

void store_row(RawImage& img, int y, const void* samples, int channels, int bits) {
  const std::uint32_t full = bits == 16 ? 65535u : 255u;
  const std::size_t w = static_cast<std::size_t>(img.width);
  if (bits == 16) {
    const auto* s = static_cast<const std::uint8_t*>(samples);
    for (std::size_t x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        std::uint16_t v;
        std::memcpy(&v, s + 2 * (x * channels + c), 2);
        store(img, x, y, channels == 1 ? -1 : c, v, full);
      }
  } else {
    const auto* s = static_cast<const std::uint8_t*>(samples);
    for (std::size_t x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) store(img, x, y, channels == 1 ? -1 : c, s[x * channels + c], full);
  }
}

void declare(RawMetadata& meta, const std::string& item) {
  if (!meta.declared_colour.empty()) meta.declared_colour += ';';
  meta.declared_colour += item;
}

}  // namespace image_detail

namespace {

bool starts_with(const std::uint8_t* d, std::size_t n, const char* sig, std::size_t len) {
  return n >= len && std::memcmp(d, sig, len) == 0;
}

/// What the first directory (IFD0) of a classic TIFF says about itself, enough to tell a camera
/// RAW from a plain image (a bounds-checked walk of IFD0's entries only).
struct Ifd0 {
  std::uint32_t width = 0, height = 0;
  int photometric = -1;
  bool dng = false;      ///< DNGVersion (50706)
  bool sub_ifds = false; ///< SubIFDs (330): where NEF, ARW and other RAWs keep their sensor data
};
Ifd0 read_ifd0(const std::uint8_t* d, std::size_t n) {
  Ifd0 out;
  if (n < 8 || !(d[0] == 'I' || d[0] == 'M')) return out;
  const bool le = d[0] == 'I';
  const auto u16 = [&](std::size_t o) {
    return static_cast<std::uint16_t>(le ? d[o] | d[o + 1] << 8 : d[o] << 8 | d[o + 1]);
  };
  const auto u32 = [&](std::size_t o) {
    return le ? static_cast<std::uint32_t>(d[o]) | static_cast<std::uint32_t>(d[o + 1]) << 8 |
                    static_cast<std::uint32_t>(d[o + 2]) << 16 | static_cast<std::uint32_t>(d[o + 3]) << 24
              : static_cast<std::uint32_t>(d[o]) << 24 | static_cast<std::uint32_t>(d[o + 1]) << 16 |
                    static_cast<std::uint32_t>(d[o + 2]) << 8 | static_cast<std::uint32_t>(d[o + 3]);
  };
  const std::size_t ifd = u32(4);
  if (ifd > n - 2) return out;
  const std::size_t count = u16(ifd);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t e = ifd + 2 + 12 * i;
    if (e + 12 > n) break;
    const std::uint16_t tag = u16(e), type = u16(e + 2);
    const std::uint32_t value = type == 3 ? u16(e + 8) : u32(e + 8);  // SHORT or LONG, inline
    if (tag == 256) out.width = value;
    else if (tag == 257) out.height = value;
    else if (tag == 262) out.photometric = static_cast<int>(value);
    else if (tag == 330) out.sub_ifds = true;
    else if (tag == 50706) out.dng = true;
  }
  return out;
}

/// Image formats no decoder here reads, by signature (name, or nullptr).
const char* unsupported_image_format(const std::uint8_t* d, std::size_t n) {
  if (starts_with(d, n, "GIF87a", 6) || starts_with(d, n, "GIF89a", 6)) return "GIF";
  if (n >= 14 && d[0] == 'B' && d[1] == 'M' && d[6] == 0 && d[7] == 0 && d[8] == 0 && d[9] == 0) return "BMP";
  if (n >= 12 && starts_with(d, n, "RIFF", 4) && std::memcmp(d + 8, "WEBP", 4) == 0) return "WebP";
  if (n >= 12 && std::memcmp(d + 4, "ftyp", 4) == 0) {
    static const char* heif[] = {"heic", "heix", "hevc", "hevx", "heim", "heis", "hevm", "hevs",
                                 "mif1", "msf1", "avif", "avis"};
    for (const char* b : heif)
      if (std::memcmp(d + 8, b, 4) == 0) return "HEIF/AVIF";
    return nullptr;  // e.g. Canon CR3 ("crx "): LibRaw's
  }
  if (starts_with(d, n, "\0\0\0\x0CjP  \r\n\x87\n", 12) || starts_with(d, n, "\xFF\x4F\xFF\x51", 4))
    return "JPEG 2000";
  if (starts_with(d, n, "\xFF\x0A", 2) || starts_with(d, n, "\0\0\0\x0CJXL \r\n\x87\n", 12)) return "JPEG XL";
  if (n >= 3 && d[0] == 'P' && d[1] >= '1' && d[1] <= '7' && (d[2] == '\n' || d[2] == ' ' || d[2] == '\r' || d[2] == '\t'))
    return "PNM (PBM/PGM/PPM/PAM)";
  if (starts_with(d, n, "\x76\x2F\x31\x01", 4)) return "OpenEXR";
  if (starts_with(d, n, "#?RADIANCE", 10) || starts_with(d, n, "#?RGBE", 6)) return "Radiance HDR";
  if (starts_with(d, n, "8BPS", 4)) return "Photoshop PSD";
  return nullptr;
}

}  // namespace

const char* file_format_name(FileFormat format) {
  switch (format) {
    case FileFormat::Raw: return "raw";
    case FileFormat::Tiff: return "tiff";
    case FileFormat::Png: return "png";
    case FileFormat::Jpeg: return "jpeg";
  }
  return "raw";
}

FileFormat detect_format(const std::uint8_t* d, std::size_t n) {
  if (d == nullptr || n == 0) throw Error(ErrorCode::EmptyFile, "the file is empty (0 bytes)");
  if (starts_with(d, n, "\x89PNG\r\n\x1a\n", 8)) return FileFormat::Png;
  if (starts_with(d, n, "\xFF\xD8\xFF", 3)) return FileFormat::Jpeg;
  const bool tiff = starts_with(d, n, "II*\0", 4) || starts_with(d, n, "MM\0*", 4);
  const bool big_tiff = starts_with(d, n, "II+\0", 4) || starts_with(d, n, "MM\0+", 4);
  if (big_tiff) return FileFormat::Tiff;  // LibRaw reads no BigTIFF
  if (tiff) {
    if (n >= 10 && d[8] == 'C' && d[9] == 'R') return FileFormat::Raw;  // Canon CR2
    const Ifd0 ifd0 = read_ifd0(d, n);
    if (ifd0.dng) return FileFormat::Raw;
    int raw_width = 0, raw_height = 0;
    if (!libraw_identifies(d, n, &raw_width, &raw_height)) return FileFormat::Tiff;
    // LibRaw also takes a plain 16-bit grey TIFF with a camera maker's Make tag for sensor data.
    // A first image that declares itself grey or RGB, has no sub-images, and is the very raster
    // LibRaw would read is the TIFF's own image.
    const bool plain = (ifd0.photometric == 1 || ifd0.photometric == 2) && !ifd0.sub_ifds &&
                       ifd0.width == static_cast<std::uint32_t>(raw_width) &&
                       ifd0.height == static_cast<std::uint32_t>(raw_height);
    return plain ? FileFormat::Tiff : FileFormat::Raw;
  }
  if (const char* other = unsupported_image_format(d, n))
    throw Error(ErrorCode::ImageUnsupported, std::string("a ") + other +
                                                 " image: only camera RAW, TIFF, PNG and JPEG files are read");
  return FileFormat::Raw;
}

RawImage decode_any(const std::uint8_t* data, std::size_t size, const DecodeOptions& raw_options,
                    const ImageDecodeOptions& image_options) {
  switch (detect_format(data, size)) {
    case FileFormat::Tiff: return decode_tiff(data, size, image_options);
    case FileFormat::Png: return decode_png(data, size, image_options);
    case FileFormat::Jpeg: return decode_jpeg(data, size, image_options);
    case FileFormat::Raw: break;
  }
  try {
    return decode_raw(data, size, raw_options);
  } catch (const Error& e) {
    // LibRaw refusing a file it does not even identify: say what else was tried.
    if (e.code() == ErrorCode::RawUnsupported && !libraw_identifies(data, size))
      throw Error(ErrorCode::RawUnsupported,
                  std::string("not a camera RAW, TIFF, PNG or JPEG file (") + e.what() + ")");
    throw;
  }
}

}  // namespace tristim

// TIFF in (libtiff, read from memory). TIFF out: profile/export_tiff.cpp.
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <sstream>
#include <vector>

#include "image_common.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

/// The file in memory, as libtiff's client procedures see it, plus libtiff's first error.
struct TiffSource {
  const std::uint8_t* data = nullptr;
  std::uint64_t size = 0, pos = 0;
  std::string error, last_error;  // libtiff's first message and its latest (on_error)
};

tmsize_t read_proc(thandle_t h, void* buf, tmsize_t n) {
  auto* s = static_cast<TiffSource*>(h);
  if (n <= 0 || s->pos >= s->size) return 0;
  const std::uint64_t k = std::min<std::uint64_t>(static_cast<std::uint64_t>(n), s->size - s->pos);
  std::memcpy(buf, s->data + s->pos, static_cast<std::size_t>(k));
  s->pos += k;
  return static_cast<tmsize_t>(k);
}
tmsize_t write_proc(thandle_t, void*, tmsize_t) { return 0; }
toff_t seek_proc(thandle_t h, toff_t off, int whence) {
  auto* s = static_cast<TiffSource*>(h);
  std::uint64_t base = whence == SEEK_CUR ? s->pos : whence == SEEK_END ? s->size : 0;
  if (off > UINT64_MAX - base) return static_cast<toff_t>(-1);
  s->pos = base + off;  // past the end is allowed (reads then return 0 bytes)
  return s->pos;
}
int close_proc(thandle_t) { return 0; }
toff_t size_proc(thandle_t h) { return static_cast<TiffSource*>(h)->size; }
int map_proc(thandle_t h, void** base, toff_t* size) {
  auto* s = static_cast<TiffSource*>(h);
  *base = const_cast<std::uint8_t*>(s->data);  // libtiff only reads a read-only mapping
  *size = s->size;
  return 1;
}
void unmap_proc(thandle_t, void*, toff_t) {}

int on_error(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  // libtiff reports some problems and reads on (an unknown tag it cannot read), so the first
  // message need not be why an operation failed: the first and the latest are kept.
  auto* s = static_cast<TiffSource*>(user);
  char buf[512];
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  (s->error.empty() ? s->error : s->last_error) = std::string(module ? module : "libtiff") + ": " + buf;
  return 1;  // handled: nothing reaches stderr
}
int on_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }  // silenced

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
struct OptionsFree {
  void operator()(TIFFOpenOptions* o) const { TIFFOpenOptionsFree(o); }
};

[[noreturn]] void corrupt(const TiffSource& src, const std::string& what) {
  throw Error(ErrorCode::ImageCorrupt,
              "the TIFF is truncated or corrupt: " + what + (src.error.empty() ? "" : " (" + src.error + (src.last_error.empty() ? "" : "; then " + src.last_error) + ")"));
}
[[noreturn]] void unsupported(const std::string& what) {
  throw Error(ErrorCode::ImageUnsupported, "this TIFF variant is not read: " + what);
}

const char* compression_name(std::uint16_t c) {
  switch (c) {
    case COMPRESSION_CCITTRLE: case COMPRESSION_CCITTFAX3: case COMPRESSION_CCITTFAX4: return "CCITT fax";
    case COMPRESSION_OJPEG: return "old-style JPEG (compression 6)";
    case COMPRESSION_NEXT: return "NeXT";
    case COMPRESSION_THUNDERSCAN: return "ThunderScan";
    case COMPRESSION_PIXARLOG: return "PixarLog";
    case COMPRESSION_SGILOG: case COMPRESSION_SGILOG24: return "SGI LogLuv";
    case COMPRESSION_JBIG: return "JBIG";
    case COMPRESSION_LZMA: return "LZMA";
    case COMPRESSION_ZSTD: return "ZSTD";
    case COMPRESSION_WEBP: return "WebP";
    case COMPRESSION_LERC: return "LERC";
    default: return nullptr;
  }
}

/// LibRaw's `flip` for a TIFF/EXIF Orientation value (the mapping dcraw uses).
int flip_of_orientation(std::uint16_t o) { return "50132467"[o & 7] - '0'; }

void read_text_tags(TIFF* tif, RawMetadata& m) {
  char* s = nullptr;
  if (TIFFGetField(tif, TIFFTAG_MAKE, &s) == 1 && s) m.make = s;
  if (TIFFGetField(tif, TIFFTAG_MODEL, &s) == 1 && s) m.model = s;
  if (TIFFGetField(tif, TIFFTAG_DATETIME, &s) == 1 && s) {
    std::tm t{};
    if (std::sscanf(s, "%d:%d:%d %d:%d:%d", &t.tm_year, &t.tm_mon, &t.tm_mday, &t.tm_hour, &t.tm_min,
                    &t.tm_sec) == 6) {
      char iso[32];
      std::snprintf(iso, sizeof iso, "%04d-%02d-%02dT%02d:%02d:%02d", t.tm_year, t.tm_mon, t.tm_mday,
                    t.tm_hour, t.tm_min, t.tm_sec);
      m.timestamp_iso = iso;
      t.tm_year -= 1900;
      t.tm_mon -= 1;
      t.tm_isdst = -1;
      m.timestamp = static_cast<std::int64_t>(std::mktime(&t));  // camera clock, as LibRaw does
    }
  }
  std::uint16_t orientation = 1;
  if (TIFFGetField(tif, TIFFTAG_ORIENTATION, &orientation) == 1) m.flip = flip_of_orientation(orientation);
  std::uint32_t icc_len = 0;
  void* icc = nullptr;
  if (TIFFGetField(tif, TIFFTAG_ICCPROFILE, &icc_len, &icc) == 1 && icc_len > 0)
    image_detail::declare(m, "ICC profile (" + std::to_string(icc_len) + " bytes)");
  std::uint16_t *tr = nullptr, *tg = nullptr, *tb = nullptr;
  if (TIFFGetField(tif, TIFFTAG_TRANSFERFUNCTION, &tr, &tg, &tb) == 1) image_detail::declare(m, "transfer function");
}

/// Exposure from the EXIF directory, if any (after the pixels: this changes the current directory).
void read_exif(TIFF* tif, RawMetadata& m) {
  toff_t exif = 0;
  if (TIFFGetField(tif, TIFFTAG_EXIFIFD, &exif) != 1 || exif == 0) return;
  if (!TIFFReadEXIFDirectory(tif, exif)) return;
  float v = 0;
  if (TIFFGetField(tif, EXIFTAG_EXPOSURETIME, &v) == 1 && v > 0) m.shutter_s = v;
  if (TIFFGetField(tif, EXIFTAG_FNUMBER, &v) == 1 && v > 0) m.f_number = v;
  std::uint16_t n = 0;
  std::uint16_t* iso = nullptr;
  if (TIFFGetField(tif, EXIFTAG_ISOSPEEDRATINGS, &n, &iso) == 1 && n > 0 && iso) m.iso = iso[0];
}

}  // namespace

RawImage decode_tiff(const std::uint8_t* data, std::size_t size, const ImageDecodeOptions& options) {
  if (data == nullptr || size == 0) throw Error(ErrorCode::EmptyFile, "the TIFF file is empty (0 bytes)");
  TiffSource src;
  src.data = data;
  src.size = size;
  std::unique_ptr<TIFFOpenOptions, OptionsFree> opts(TIFFOpenOptionsAlloc());
  TIFFOpenOptionsSetErrorHandlerExtR(opts.get(), on_error, &src);
  TIFFOpenOptionsSetWarningHandlerExtR(opts.get(), on_warning, &src);
  // No single allocation over 1 GiB, whatever a corrupt header claims (64 MP of 16-bit RGB in
  // one strip is 384 MiB).
  TIFFOpenOptionsSetMaxSingleMemAlloc(opts.get(), tmsize_t(1) << 30);
  std::unique_ptr<TIFF, TiffCloser> tif(TIFFClientOpenExt("TIFF", "r", &src, read_proc, write_proc, seek_proc,
                                                          close_proc, size_proc, map_proc, unmap_proc, opts.get()));
  if (!tif) corrupt(src, "its header or first directory cannot be read");
  TIFF* t = tif.get();

  std::uint32_t width = 0, height = 0;
  std::uint16_t bps = 1, spp = 1, photometric = 0, planar = PLANARCONFIG_CONTIG, format = SAMPLEFORMAT_UINT,
                compression = COMPRESSION_NONE, n_extra = 0;
  std::uint16_t* extra = nullptr;
  if (TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &width) != 1 || TIFFGetField(t, TIFFTAG_IMAGELENGTH, &height) != 1)
    corrupt(src, "no image width or height");
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bps);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &planar);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
  TIFFGetFieldDefaulted(t, TIFFTAG_EXTRASAMPLES, &n_extra, &extra);
  if (TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric) != 1) corrupt(src, "no PhotometricInterpretation tag");

  // What is read: the same set natively and in wasm (cmake/wasm_third_party.cmake builds these codecs).
  switch (compression) {
    case COMPRESSION_NONE: case COMPRESSION_LZW: case COMPRESSION_PACKBITS:
    case COMPRESSION_ADOBE_DEFLATE: case COMPRESSION_DEFLATE: case COMPRESSION_JPEG:
      break;
    default: {
      const char* name = compression_name(compression);
      unsupported(std::string(name ? name : "an unknown") + " compression (" + std::to_string(compression) + ")");
    }
  }
  if (n_extra > 0)
    unsupported(std::to_string(spp) + " samples per pixel with " + std::to_string(n_extra) +
                " extra (alpha or other) samples: save the image without an alpha channel");
  int channels = 0;
  switch (photometric) {
    case PHOTOMETRIC_MINISBLACK: channels = 1; break;
    case PHOTOMETRIC_RGB: channels = 3; break;
    case PHOTOMETRIC_YCBCR:
      if (compression != COMPRESSION_JPEG) unsupported("YCbCr samples without JPEG compression");
      // JPEG in TIFF: libjpeg-turbo converts YCbCr to RGB, as it does for a JPEG file.
      if (!TIFFSetField(t, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB)) corrupt(src, "JPEG colour mode");
      channels = 3;
      break;
    case PHOTOMETRIC_MINISWHITE: unsupported("min-is-white (inverted) grey");
    case PHOTOMETRIC_PALETTE: unsupported("palette (indexed) colour");
    case PHOTOMETRIC_SEPARATED: unsupported("CMYK (separated) colour");
    case PHOTOMETRIC_CIELAB: case PHOTOMETRIC_ICCLAB: case PHOTOMETRIC_ITULAB: unsupported("CIELab samples");
    case PHOTOMETRIC_MASK: unsupported("a transparency mask");
    case PHOTOMETRIC_CFA: case 34892:  // LinearRaw (DNG)
      unsupported("CFA or linear RAW data outside a DNG (photometric " + std::to_string(photometric) + ")");
    default: unsupported("photometric interpretation " + std::to_string(photometric));
  }
  if (spp != channels)
    unsupported(std::to_string(spp) + " samples per pixel for " + (channels == 1 ? "grey" : "RGB"));
  if (bps != 8 && bps != 16) unsupported(std::to_string(bps) + "-bit samples (8 and 16 bits are read)");
  if (format != SAMPLEFORMAT_UINT)
    unsupported(std::string(format == SAMPLEFORMAT_IEEEFP ? "floating-point" : format == SAMPLEFORMAT_INT ? "signed integer" : "non-integer") +
                " samples (unsigned integers are read)");
  if (compression == COMPRESSION_JPEG && bps != 8) unsupported("JPEG compression of " + std::to_string(bps) + "-bit samples");

  // The pixels are allocated once the first strip or tile has decoded (a corrupt file is refused
  // without an image-sized allocation); the refusals and their order are as before.
  RawImage img = image_detail::new_image_header("tiff", width, height, channels, bps, options);
  read_text_tags(t, img.meta);

  // Decode every strip or tile (either planar configuration) and place its samples.
  const bool separate = planar == PLANARCONFIG_SEPARATE && channels > 1;
  const int planes = separate ? channels : 1;
  const int per_pixel = separate ? 1 : channels;
  const std::uint32_t full = bps == 16 ? 65535u : 255u;
  const std::size_t bytes = bps / 8;
  const bool tiled = TIFFIsTiled(t) != 0;
  std::uint32_t cw = width, ch = 0;  // chunk (strip or tile) width and height
  if (tiled) {
    if (TIFFGetField(t, TIFFTAG_TILEWIDTH, &cw) != 1 || TIFFGetField(t, TIFFTAG_TILELENGTH, &ch) != 1 || cw == 0 || ch == 0)
      corrupt(src, "no tile size");
    // A header's tile size is not bounded by its image size, and one tile's buffer is allocated
    // from it (fuzz_tiff: a 403-byte file asked for 3.5 GB): a tile may not exceed the image limit.
    const double tile_mp = static_cast<double>(cw) * ch / 1e6;
    if (tile_mp > options.max_megapixels) {
      std::ostringstream ss;
      ss << "the TIFF's tiles are " << cw << " x " << ch << " pixels (" << tile_mp << " MP), over the limit of "
         << options.max_megapixels << " MP";
      throw Error(ErrorCode::LimitExceeded, ss.str());
    }
  } else {
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &ch);
    ch = std::max<std::uint32_t>(1, std::min(ch, height));
  }
  const tmsize_t chunk = tiled ? TIFFTileSize(t) : TIFFStripSize(t);
  const std::size_t row_bytes = static_cast<std::size_t>(cw) * per_pixel * bytes;
  if (chunk <= 0 || static_cast<std::uint64_t>(chunk) < static_cast<std::uint64_t>(row_bytes)) corrupt(src, "inconsistent strip or tile size");
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(chunk));
  for (int p = 0; p < planes; ++p)
    for (std::uint32_t y0 = 0; y0 < height; y0 += ch)
      for (std::uint32_t x0 = 0; x0 < width; x0 += cw) {
        const std::uint32_t rows = std::min(ch, height - y0);
        const std::uint32_t cols = std::min(cw, width - x0);
        tmsize_t got;
        std::uint32_t index;
        if (tiled) {
          index = TIFFComputeTile(t, x0, y0, 0, static_cast<std::uint16_t>(p));
          got = TIFFReadEncodedTile(t, index, buf.data(), chunk);
        } else {
          index = TIFFComputeStrip(t, y0, static_cast<std::uint16_t>(p));
          got = TIFFReadEncodedStrip(t, index, buf.data(), static_cast<tmsize_t>(rows * row_bytes));
        }
        const std::uint64_t need = tiled ? static_cast<std::uint64_t>(chunk) : static_cast<std::uint64_t>(rows) * row_bytes;
        if (got < 0 || static_cast<std::uint64_t>(got) < need)
          corrupt(src, std::string(tiled ? "tile " : "strip ") + std::to_string(index) + " cannot be decoded in full");
        if (img.rgb.empty()) image_detail::allocate_pixels(img);
        for (std::uint32_t r = 0; r < rows; ++r) {
          const std::uint8_t* line = buf.data() + r * row_bytes;
          for (std::uint32_t x = 0; x < cols; ++x)
            for (int s = 0; s < per_pixel; ++s) {
              const std::uint8_t* q = line + (static_cast<std::size_t>(x) * per_pixel + s) * bytes;
              std::uint32_t v = q[0];
              if (bytes == 2) {
                std::uint16_t w16;
                std::memcpy(&w16, q, 2);  // libtiff has already swapped to the host's order
                v = w16;
              }
              const int c = channels == 1 ? -1 : separate ? p : s;
              image_detail::store(img, x0 + x, y0 + r, c, v, full);
            }
        }
      }
  read_exif(t, img.meta);
  return img;
}

}  // namespace tristim

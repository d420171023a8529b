// Float TIFF out (profile/export.hpp: float_tiff, float_tiff_bands), written by libtiff into memory:
// the XYZ images of `apply` and `absolute`, the spectral images of `linearise --spectral`, and the
// page's downloads. The layout is the one the exports have always had (little-endian, 32-bit IEEE
// float samples, chunky, uncompressed, one strip), so a reader may find the pixels verbatim at
// StripOffsets; libtiff writes the directory after the pixels.
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "tristim/error.hpp"
#include "../host_endian.hpp"
#include "tristim/profile/export.hpp"

namespace tristim {

namespace {

/// The file being written, as libtiff's client procedures see it, plus libtiff's first error.
struct TiffSink {
  std::vector<std::uint8_t> bytes;  ///< bytes.size() is the file's length so far
  std::uint64_t pos = 0;
  std::string error;
};

tmsize_t sink_read(thandle_t h, void* buf, tmsize_t n) {
  auto* s = static_cast<TiffSink*>(h);
  if (n <= 0 || s->pos >= s->bytes.size()) return 0;
  const std::uint64_t k = std::min<std::uint64_t>(static_cast<std::uint64_t>(n), s->bytes.size() - s->pos);
  std::memcpy(buf, s->bytes.data() + s->pos, static_cast<std::size_t>(k));
  s->pos += k;
  return static_cast<tmsize_t>(k);
}
tmsize_t sink_write(thandle_t h, void* buf, tmsize_t n) {
  auto* s = static_cast<TiffSink*>(h);
  if (n <= 0) return 0;
  const std::uint64_t end = s->pos + static_cast<std::uint64_t>(n);
  if (end > s->bytes.size()) s->bytes.resize(static_cast<std::size_t>(end));
  std::memcpy(s->bytes.data() + s->pos, buf, static_cast<std::size_t>(n));
  s->pos = end;
  return n;
}
toff_t sink_seek(thandle_t h, toff_t off, int whence) {
  auto* s = static_cast<TiffSink*>(h);
  const std::uint64_t base = whence == SEEK_CUR ? s->pos : whence == SEEK_END ? s->bytes.size() : 0;
  if (off > UINT64_MAX - base) return static_cast<toff_t>(-1);
  s->pos = base + off;  // past the end: the gap is zero-filled by the next write
  return s->pos;
}
int sink_close(thandle_t) { return 0; }
toff_t sink_size(thandle_t h) { return static_cast<TiffSink*>(h)->bytes.size(); }
int sink_map(thandle_t, void**, toff_t*) { return 0; }  // no mapping: libtiff reads through sink_read
void sink_unmap(thandle_t, void*, toff_t) {}

int on_error(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  auto* s = static_cast<TiffSink*>(user);
  if (s->error.empty()) {
    char buf[512];
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    s->error = std::string(module ? module : "libtiff") + ": " + buf;
  }
  return 1;  // handled: nothing reaches stderr
}
int on_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

struct OptionsFree {
  void operator()(TIFFOpenOptions* o) const { TIFFOpenOptionsFree(o); }
};

/// `bands` interleaved float samples per pixel; Photometric RGB for 3 bands when `rgb`, else
/// MinIsBlack with bands − 1 unspecified ExtraSamples (how multispectral TIFFs are written).
std::vector<std::uint8_t> write_float_tiff(const float* pixels, int width, int height, int bands, bool rgb,
                                           const std::string& description) {
  if (width <= 0 || height <= 0 || !pixels) throw Error(ErrorCode::InvalidArgument, "image writer: empty image");
  if (bands < 1 || bands > 1000) throw Error(ErrorCode::InvalidArgument, "TIFF: 1..1000 bands");
  const std::uint64_t row_bytes = static_cast<std::uint64_t>(width) * 4 * static_cast<std::uint64_t>(bands);
  const std::uint64_t data_bytes = row_bytes * static_cast<std::uint64_t>(height);
  // Classic TIFF addresses 4 GB; one strip's byte count is a LONG.
  if (data_bytes > 0xF0000000ULL) throw Error(ErrorCode::ExportFailed, "TIFF: image larger than 4 GB");

  const int extra = rgb ? bands - 3 : bands - 1;
  const std::vector<std::uint16_t> kinds(static_cast<std::size_t>(std::max(extra, 0)), EXTRASAMPLE_UNSPECIFIED);
  TiffSink sink;
  sink.bytes.reserve(static_cast<std::size_t>(data_bytes) + 4 * static_cast<std::size_t>(bands) + description.size() + 4096);
  std::unique_ptr<TIFFOpenOptions, OptionsFree> opts(TIFFOpenOptionsAlloc());
  TIFFOpenOptionsSetErrorHandlerExtR(opts.get(), on_error, &sink);
  TIFFOpenOptionsSetWarningHandlerExtR(opts.get(), on_warning, &sink);
  // "wl": write, little-endian whatever the host.
  TIFF* t = TIFFClientOpenExt("export.tif", "wl", &sink, sink_read, sink_write, sink_seek, sink_close, sink_size,
                              sink_map, sink_unmap, opts.get());
  auto fail = [&](const char* what) {
    throw Error(ErrorCode::ExportFailed, std::string("TIFF: ") + what + (sink.error.empty() ? "" : " (" + sink.error + ")"));
  };
  if (!t) fail("libtiff could not start the file");
  const auto nb = static_cast<std::uint16_t>(bands);
  bool ok = TIFFSetField(t, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(width)) == 1 &&
            TIFFSetField(t, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(height)) == 1 &&
            TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, nb) == 1 &&
            TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, std::uint16_t(32)) == 1 &&
            TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, std::uint16_t(SAMPLEFORMAT_IEEEFP)) == 1 &&
            TIFFSetField(t, TIFFTAG_COMPRESSION, std::uint16_t(COMPRESSION_NONE)) == 1 &&
            TIFFSetField(t, TIFFTAG_PLANARCONFIG, std::uint16_t(PLANARCONFIG_CONTIG)) == 1 &&
            TIFFSetField(t, TIFFTAG_PHOTOMETRIC, std::uint16_t(rgb ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK)) == 1 &&
            TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, static_cast<std::uint32_t>(height)) == 1 &&
            TIFFSetField(t, TIFFTAG_IMAGEDESCRIPTION, description.c_str()) == 1;
  if (ok && extra > 0)
    ok = TIFFSetField(t, TIFFTAG_EXTRASAMPLES, static_cast<std::uint16_t>(extra), kinds.data()) == 1;
  // The pixels as the one strip's raw bytes: libtiff neither buffers nor copies them. TIFFWriteRawStrip
  // writes them as given, so on a big-endian host (none we build for) they are swapped first.
  std::vector<float> swapped;
  const float* strip = pixels;
  if (ok && (TIFFIsBigEndian(t) != 0) == host_is_little_endian()) {
    swapped.assign(pixels, pixels + data_bytes / 4);
    TIFFSwabArrayOfFloat(swapped.data(), static_cast<tmsize_t>(swapped.size()));
    strip = swapped.data();
  }
  if (ok) ok = TIFFWriteRawStrip(t, 0, const_cast<float*>(strip), static_cast<tmsize_t>(data_bytes)) == static_cast<tmsize_t>(data_bytes);
  if (!ok) {
    TIFFCleanup(t);
    fail("libtiff refused the image");
  }
  TIFFClose(t);  // writes the directory
  if (!sink.error.empty()) fail("libtiff could not write the directory");
  return std::move(sink.bytes);
}

}  // namespace

std::vector<std::uint8_t> float_tiff(const float* pixels, int width, int height, const std::string& description) {
  return write_float_tiff(pixels, width, height, 3, true, description);
}

std::vector<std::uint8_t> float_tiff_bands(const float* pixels, int width, int height, int bands,
                                           const std::string& description) {
  return write_float_tiff(pixels, width, height, bands, false, description);
}

}  // namespace tristim

// PNG in (libpng, read from memory): the only file that includes png.h.
//
// libpng reports errors by longjmp (error_fn) to the setjmp in the protected_* function that made
// the call; every C++ object lives in the PngJob or in read(), outside those functions, so nothing
// is left indeterminate and no destructor is skipped.
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstring>
#include <sstream>
#include <vector>

#include "image_common.hpp"
#include "../host_endian.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

struct PngJob {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0, pos = 0;
  std::string error;  ///< libpng's message
  ImageDecodeOptions options;
  RawImage image;
  std::vector<std::uint8_t> pixels;
  std::vector<png_bytep> rows;
};

void read_fn(png_structp png, png_bytep out, size_t n) {
  auto* job = static_cast<PngJob*>(png_get_io_ptr(png));
  if (n > job->size - job->pos) png_error(png, "the file ends early");
  std::memcpy(out, job->data + job->pos, n);
  job->pos += n;
}
void error_fn(png_structp png, png_const_charp message) {
  auto* job = static_cast<PngJob*>(png_get_error_ptr(png));
  if (job->error.empty()) job->error = message ? message : "libpng error";
  png_longjmp(png, 1);
}
void warning_fn(png_structp, png_const_charp) {}  // ancillary-chunk problems: silenced

// libpng's error path is a longjmp to the setjmp of the protected_* function running at the time.
// Each holds one setjmp and libpng calls only, with plain values in and out: no C++ object with a
// destructor and no call that can throw. A longjmp then skips no destructor, and the function has
// no exception landing pad, which native wasm exceptions require of a function that calls setjmp
// (LLVM 14 refuses the mix). The C++ work (checks, Error, the image) runs between them, in read().

/// What png_read_info tells about the image, as plain values.
struct PngHeader {
  png_uint_32 width = 0, height = 0;
  int depth = 0, colour = 0, interlace = 0;
  bool iccp = false;
  png_charp iccp_name = nullptr;  ///< owned by libpng's info structure
  png_uint_32 iccp_len = 0;
  bool srgb = false, gamma_valid = false;
  double gamma = 0;
};

bool protected_read_info(PngJob* job, png_structp png, png_infop info, PngHeader* h) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, job, read_fn);
  png_set_user_limits(png, 0x7fffffff, 0x7fffffff);  // new_image applies the megapixel limit
  png_read_info(png, info);
  png_get_IHDR(png, info, &h->width, &h->height, &h->depth, &h->colour, &h->interlace, nullptr, nullptr);
  if (png_get_valid(png, info, PNG_INFO_iCCP)) {
    int method = 0;
    png_bytep profile = nullptr;
    h->iccp = true;
    png_get_iCCP(png, info, &h->iccp_name, &method, &profile, &h->iccp_len);
  }
  h->srgb = png_get_valid(png, info, PNG_INFO_sRGB) != 0;
  h->gamma_valid = png_get_valid(png, info, PNG_INFO_gAMA) && png_get_gAMA(png, info, &h->gamma);
  return true;
}

bool protected_start_rows(png_structp png, png_infop info, bool swap, int* passes, std::size_t* row_bytes) {
  if (setjmp(png_jmpbuf(png))) return false;
  if (swap) png_set_swap(png);  // PNG is big-endian
  *passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  *row_bytes = png_get_rowbytes(png, info);
  return true;
}

bool protected_read_row(png_structp png, png_bytep row) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_row(png, row, nullptr);
  return true;
}

bool protected_read_image(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  return true;
}

bool protected_read_end(png_structp png) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_end(png, nullptr);  // the chunks after the image, up to IEND, with their CRCs
  return true;
}

/// Reads the whole image into job->image; false if libpng gave up (message in job->error).
/// Refusals of a format variant throw (from this frame; no libpng frame lies in between).
bool read(PngJob* job, png_structp png, png_infop info) {
  PngHeader h;
  if (!protected_read_info(job, png, info, &h)) return false;
  int channels = 0;
  switch (h.colour) {
    case PNG_COLOR_TYPE_GRAY: channels = 1; break;
    case PNG_COLOR_TYPE_RGB: channels = 3; break;
    case PNG_COLOR_TYPE_PALETTE:
      throw Error(ErrorCode::ImageUnsupported, "this PNG variant is not read: palette (indexed) colour; save it as RGB");
    case PNG_COLOR_TYPE_GRAY_ALPHA: case PNG_COLOR_TYPE_RGB_ALPHA:
      throw Error(ErrorCode::ImageUnsupported,
                  "this PNG variant is not read: an alpha channel; save the image without transparency");
    default:
      throw Error(ErrorCode::ImageUnsupported, "this PNG variant is not read: colour type " + std::to_string(h.colour));
  }
  const int depth = h.depth;
  if (depth != 8 && depth != 16)
    throw Error(ErrorCode::ImageUnsupported,
                "this PNG variant is not read: " + std::to_string(depth) + "-bit grey (8 and 16 bits are read)");
  job->image = image_detail::new_image("png", h.width, h.height, channels, depth, job->options);
  RawMetadata& m = job->image.meta;
  if (h.iccp)
    image_detail::declare(m, "ICC profile '" + std::string(h.iccp_name ? h.iccp_name : "") + "' (" +
                                 std::to_string(h.iccp_len) + " bytes)");
  if (h.srgb) image_detail::declare(m, "sRGB");
  if (h.gamma_valid) {
    std::ostringstream ss;
    ss << "gamma " << h.gamma;
    image_detail::declare(m, ss.str());
  }

  int passes = 0;
  std::size_t row_bytes = 0;
  if (!protected_start_rows(png, info, depth == 16 && host_is_little_endian(), &passes, &row_bytes)) return false;
  if (row_bytes != static_cast<std::size_t>(h.width) * channels * (depth / 8)) {
    job->error = "unexpected row size";
    return false;
  }
  const png_uint_32 height = h.height;
  if (passes == 1) {
    job->pixels.resize(row_bytes);
    for (png_uint_32 y = 0; y < height; ++y) {
      if (!protected_read_row(png, job->pixels.data())) return false;
      image_detail::store_row(job->image, static_cast<int>(y), job->pixels.data(), channels, depth);
    }
  } else {  // Adam7: the passes fill the whole image
    job->pixels.resize(row_bytes * height);
    job->rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) job->rows[y] = job->pixels.data() + y * row_bytes;
    if (!protected_read_image(png, job->rows.data())) return false;
    for (png_uint_32 y = 0; y < height; ++y)
      image_detail::store_row(job->image, static_cast<int>(y), job->rows[y], channels, depth);
  }
  return protected_read_end(png);
}

struct PngFree {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngFree() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

}  // namespace

RawImage decode_png(const std::uint8_t* data, std::size_t size, const ImageDecodeOptions& options) {
  if (data == nullptr || size == 0) throw Error(ErrorCode::EmptyFile, "the PNG file is empty (0 bytes)");
  if (png_sig_cmp(data, 0, std::min<std::size_t>(size, 8)) != 0)
    throw Error(ErrorCode::ImageCorrupt, "not a PNG: the 8-byte signature is wrong");
  PngJob job;
  job.data = data;
  job.size = size;
  job.options = options;
  PngFree guard;
  guard.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, error_fn, warning_fn);
  if (!guard.png) throw Error(ErrorCode::Internal, "libpng: cannot create a read structure");
  guard.info = png_create_info_struct(guard.png);
  if (!guard.info) throw Error(ErrorCode::Internal, "libpng: cannot create an info structure");
  if (!read(&job, guard.png, guard.info))
    throw Error(ErrorCode::ImageCorrupt, "the PNG is truncated or corrupt: " + job.error + " (at byte " +
                                             std::to_string(job.pos) + " of " + std::to_string(size) + ")");
  return std::move(job.image);
}

}  // namespace tristim

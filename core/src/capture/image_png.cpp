// PNG in (libpng, read from memory): the only file that includes png.h.
//
// libpng reports errors by longjmp to the setjmp in run(); every C++ object run() touches lives
// in the PngJob behind a pointer set before setjmp, so nothing is left indeterminate, and no C++
// frame with a destructor lies between libpng's error call and run().
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstring>
#include <sstream>
#include <vector>

#include "image_common.hpp"
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

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

/// Reads the whole image into job->image; false if libpng gave up (message in job->error).
/// Refusals of a format variant throw (before any longjmp can happen, from this C++ frame).
bool run(PngJob* job, png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, job, read_fn);
  png_set_user_limits(png, 0x7fffffff, 0x7fffffff);  // new_image applies the megapixel limit
  png_read_info(png, info);
  png_uint_32 width = 0, height = 0;
  int depth = 0, colour = 0, interlace = 0;
  png_get_IHDR(png, info, &width, &height, &depth, &colour, &interlace, nullptr, nullptr);
  int channels = 0;
  switch (colour) {
    case PNG_COLOR_TYPE_GRAY: channels = 1; break;
    case PNG_COLOR_TYPE_RGB: channels = 3; break;
    case PNG_COLOR_TYPE_PALETTE:
      throw Error(ErrorCode::ImageUnsupported, "this PNG variant is not read: palette (indexed) colour; save it as RGB");
    case PNG_COLOR_TYPE_GRAY_ALPHA: case PNG_COLOR_TYPE_RGB_ALPHA:
      throw Error(ErrorCode::ImageUnsupported,
                  "this PNG variant is not read: an alpha channel; save the image without transparency");
    default:
      throw Error(ErrorCode::ImageUnsupported, "this PNG variant is not read: colour type " + std::to_string(colour));
  }
  if (depth != 8 && depth != 16)
    throw Error(ErrorCode::ImageUnsupported,
                "this PNG variant is not read: " + std::to_string(depth) + "-bit grey (8 and 16 bits are read)");
  job->image = image_detail::new_image("png", width, height, channels, depth, job->options);
  RawMetadata& m = job->image.meta;
  if (png_get_valid(png, info, PNG_INFO_iCCP)) {
    png_charp name = nullptr;
    int method = 0;
    png_bytep profile = nullptr;
    png_uint_32 len = 0;
    png_get_iCCP(png, info, &name, &method, &profile, &len);
    image_detail::declare(m, "ICC profile '" + std::string(name ? name : "") + "' (" + std::to_string(len) + " bytes)");
  }
  if (png_get_valid(png, info, PNG_INFO_sRGB)) image_detail::declare(m, "sRGB");
  double gamma = 0;
  if (png_get_valid(png, info, PNG_INFO_gAMA) && png_get_gAMA(png, info, &gamma)) {
    std::ostringstream ss;
    ss << "gamma " << gamma;
    image_detail::declare(m, ss.str());
  }

  if (depth == 16 && host_is_little_endian()) png_set_swap(png);  // PNG is big-endian
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  if (row_bytes != static_cast<std::size_t>(width) * channels * (depth / 8))
    png_error(png, "unexpected row size");
  if (passes == 1) {
    job->pixels.resize(row_bytes);
    for (png_uint_32 y = 0; y < height; ++y) {
      png_read_row(png, job->pixels.data(), nullptr);
      image_detail::store_row(job->image, static_cast<int>(y), job->pixels.data(), channels, depth);
    }
  } else {  // Adam7: the passes fill the whole image
    job->pixels.resize(row_bytes * height);
    job->rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) job->rows[y] = job->pixels.data() + y * row_bytes;
    png_read_image(png, job->rows.data());
    for (png_uint_32 y = 0; y < height; ++y)
      image_detail::store_row(job->image, static_cast<int>(y), job->rows[y], channels, depth);
  }
  png_read_end(png, nullptr);  // the chunks after the image, up to IEND, with their CRCs
  return true;
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
  if (!run(&job, guard.png, guard.info))
    throw Error(ErrorCode::ImageCorrupt, "the PNG is truncated or corrupt: " + job.error + " (at byte " +
                                             std::to_string(job.pos) + " of " + std::to_string(size) + ")");
  return std::move(job.image);
}

}  // namespace tristim

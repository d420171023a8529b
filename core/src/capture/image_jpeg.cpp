// JPEG in (libjpeg-turbo, read from memory): the only file that includes jpeglib.h.
//
// libjpeg reports fatal errors through error_exit, which must not return: it longjmps to the
// setjmp in the protected_* function that made the call. Every C++ object lives in the JpegJob or
// in read(), outside those functions (see image_png.cpp for the same pattern).
#include <cstdio>  // jpeglib.h needs FILE and size_t first
#include <cstdlib>
#include <csetjmp>
#include <cstring>
#include <vector>

#include <jpeglib.h>
#include <jerror.h>

#include "image_common.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

constexpr int kMaxScans = 1000;  ///< progressive scans; more is a denial of service, not a photo

struct JpegJob {
  jpeg_error_mgr err{};           // first member: libjpeg's err pointer is also the job's
  jpeg_progress_mgr progress{};
  std::jmp_buf jump;
  int fatal_code = 0;             ///< libjpeg's msg_code of the error that stopped it
  bool too_many_scans = false;
  std::string fatal;
  bool created = false;           ///< jpeg_create_decompress done (jpeg_destroy_decompress due)
  int corrupt_warnings = 0;
  std::string first_warning;
  ImageDecodeOptions options;
  RawImage image;
  std::vector<JSAMPLE> row;
};

JpegJob* job_of(j_common_ptr c) { return reinterpret_cast<JpegJob*>(c->err); }

std::string message_of(j_common_ptr c) {
  char buf[JMSG_LENGTH_MAX];
  (*c->err->format_message)(c, buf);
  return buf;
}

void error_exit(j_common_ptr c) {
  JpegJob* job = job_of(c);
  job->fatal_code = c->err->msg_code;
  job->fatal = message_of(c);
  std::longjmp(job->jump, 1);
}

/// Warnings (level -1) that mean the entropy-coded data is damaged: libjpeg carries on with
/// grey blocks, we refuse the file. Others (an unknown JFIF revision, extraneous bytes between
/// markers, a bad ICC marker) are harmless to the pixels and ignored.
void emit_message(j_common_ptr c, int level) {
  if (level >= 0) return;  // trace messages
  switch (c->err->msg_code) {
    case JWRN_ARITH_BAD_CODE: case JWRN_BOGUS_PROGRESSION: case JWRN_HIT_MARKER: case JWRN_HUFF_BAD_CODE:
    case JWRN_JPEG_EOF: case JWRN_MUST_RESYNC: case JWRN_NOT_SEQUENTIAL: case JWRN_TOO_MUCH_DATA: {
      JpegJob* job = job_of(c);
      if (job->corrupt_warnings++ == 0) job->first_warning = message_of(c);
      break;
    }
    default: break;
  }
}
void output_message(j_common_ptr) {}  // nothing reaches stderr

void progress_monitor(j_common_ptr c) {
  if (!c->is_decompressor) return;
  if (reinterpret_cast<j_decompress_ptr>(c)->input_scan_number > kMaxScans) {
    JpegJob* job = job_of(c);
    job->too_many_scans = true;
    std::longjmp(job->jump, 1);
  }
}

// libjpeg's error path is a longjmp (error_exit, progress_monitor) to the setjmp of the
// protected_* function running at the time. Each holds one setjmp and libjpeg calls only, with
// plain values in and out: no C++ object with a destructor and no call that can throw. A longjmp
// then skips no destructor, and the function has no exception landing pad, which native wasm
// exceptions require of a function that calls setjmp (LLVM 14 refuses the mix). The C++ work
// (checks, Error, the image) runs between them, in read().

bool protected_read_header(JpegJob* job, j_decompress_ptr cinfo, const std::uint8_t* data, std::size_t size,
                           int* header) {
  if (setjmp(job->jump)) return false;
  jpeg_create_decompress(cinfo);  // may fail (out of memory): after setjmp
  job->created = true;
  job->progress.progress_monitor = progress_monitor;
  cinfo->progress = &job->progress;
  cinfo->mem->max_memory_to_use = 1L << 30;  // 1 GiB for libjpeg's own buffers, whatever the header says
  jpeg_mem_src(cinfo, data, static_cast<unsigned long>(size));
  jpeg_save_markers(cinfo, JPEG_APP0 + 2, 0xFFFF);  // ICC profile chunks, to report them
  *header = jpeg_read_header(cinfo, TRUE);
  return true;
}

bool protected_read_icc(JpegJob* job, j_decompress_ptr cinfo, JOCTET** icc, unsigned int* icc_len, bool* found) {
  if (setjmp(job->jump)) return false;
  *found = jpeg_read_icc_profile(cinfo, icc, icc_len) != 0;
  return true;
}

bool protected_start(JpegJob* job, j_decompress_ptr cinfo) {
  if (setjmp(job->jump)) return false;
  jpeg_start_decompress(cinfo);  // a progressive JPEG is read whole here
  return true;
}

bool protected_read_row(JpegJob* job, j_decompress_ptr cinfo, JSAMPROW row, JDIMENSION* got) {
  if (setjmp(job->jump)) return false;
  JSAMPROW rows[1] = {row};
  *got = jpeg_read_scanlines(cinfo, rows, 1);
  return true;
}

bool protected_finish(JpegJob* job, j_decompress_ptr cinfo) {
  if (setjmp(job->jump)) return false;
  jpeg_finish_decompress(cinfo);
  return true;
}

/// Decodes into job->image; false if libjpeg stopped (job->fatal_code / too_many_scans say why).
/// Refusals of a format variant throw from this frame (no libjpeg frame in between).
bool read(JpegJob* job, j_decompress_ptr cinfo, const std::uint8_t* data, std::size_t size) {
  int header = 0;
  if (!protected_read_header(job, cinfo, data, size, &header)) return false;
  if (header != JPEG_HEADER_OK) throw Error(ErrorCode::ImageCorrupt, "the JPEG holds tables but no image");
  int channels = 0;
  if (cinfo->num_components == 1) {
    channels = 1;
    cinfo->out_color_space = JCS_GRAYSCALE;
  } else if (cinfo->num_components == 3 &&
             (cinfo->jpeg_color_space == JCS_YCbCr || cinfo->jpeg_color_space == JCS_RGB)) {
    channels = 3;
    cinfo->out_color_space = JCS_RGB;
  } else {
    const bool cmyk = cinfo->jpeg_color_space == JCS_CMYK || cinfo->jpeg_color_space == JCS_YCCK;
    throw Error(ErrorCode::ImageUnsupported,
                std::string("this JPEG variant is not read: ") +
                    (cmyk ? "CMYK/YCCK colour" : std::to_string(cinfo->num_components) + " colour components") +
                    " (grey and RGB/YCbCr are read)");
  }
  // Pixels allocated after jpeg_start_decompress: a file libjpeg gives up on there (a progressive
  // JPEG is read whole there) is refused without an image-sized allocation.
  job->image = image_detail::new_image_header("jpeg", cinfo->image_width, cinfo->image_height, channels, 8, job->options);
  JOCTET* icc = nullptr;
  unsigned int icc_len = 0;
  bool found_icc = false;
  if (!protected_read_icc(job, cinfo, &icc, &icc_len, &found_icc)) return false;
  if (found_icc) {
    std::free(icc);
    image_detail::declare(job->image.meta, "ICC profile (" + std::to_string(icc_len) + " bytes)");
  }
  if (cinfo->saw_Adobe_marker && cinfo->jpeg_color_space == JCS_RGB) image_detail::declare(job->image.meta, "RGB (no YCbCr transform)");
  // The accurate integer IDCT and libjpeg's default (fancy) upsampling: bit-exact between
  // libjpeg-turbo's SIMD (native) and plain C (wasm) paths.
  cinfo->dct_method = JDCT_ISLOW;
  cinfo->do_fancy_upsampling = TRUE;
  if (!protected_start(job, cinfo)) return false;
  image_detail::allocate_pixels(job->image);
  job->row.resize(static_cast<std::size_t>(cinfo->output_width) * cinfo->output_components);
  while (cinfo->output_scanline < cinfo->output_height) {
    const JDIMENSION y = cinfo->output_scanline;
    JDIMENSION got = 0;
    if (!protected_read_row(job, cinfo, job->row.data(), &got)) return false;
    if (got != 1) break;
    image_detail::store_row(job->image, static_cast<int>(y), job->row.data(), channels, 8);
  }
  return protected_finish(job, cinfo);
}

struct JpegFree {
  JpegJob* job;
  jpeg_decompress_struct* cinfo;
  ~JpegFree() {
    if (job->created) jpeg_destroy_decompress(cinfo);
  }
};

}  // namespace

RawImage decode_jpeg(const std::uint8_t* data, std::size_t size, const ImageDecodeOptions& options) {
  if (data == nullptr || size == 0) throw Error(ErrorCode::EmptyFile, "the JPEG file is empty (0 bytes)");
  JpegJob job;
  job.options = options;
  jpeg_decompress_struct cinfo{};
  cinfo.err = jpeg_std_error(&job.err);
  job.err.error_exit = error_exit;
  job.err.emit_message = emit_message;
  job.err.output_message = output_message;
  JpegFree guard{&job, &cinfo};
  if (!read(&job, &cinfo, data, size)) {
    if (job.too_many_scans)
      throw Error(ErrorCode::LimitExceeded,
                  "the JPEG has more than " + std::to_string(kMaxScans) + " progressive scans");
    switch (job.fatal_code) {
      case JERR_BAD_PRECISION: case JERR_SOF_UNSUPPORTED: case JERR_ARITH_NOTIMPL: case JERR_NOT_COMPILED:
      case JERR_NOTIMPL: case JERR_CONVERSION_NOTIMPL:
        throw Error(ErrorCode::ImageUnsupported, "this JPEG variant is not read: " + job.fatal);
      case JERR_IMAGE_TOO_BIG: case JERR_WIDTH_OVERFLOW: case JERR_OUT_OF_MEMORY: case JERR_NO_BACKING_STORE:
        throw Error(ErrorCode::LimitExceeded, "the JPEG needs too much memory: " + job.fatal);
      default:
        throw Error(ErrorCode::ImageCorrupt, "the JPEG is truncated or corrupt: " + job.fatal);
    }
  }
  if (job.corrupt_warnings > 0)
    throw Error(ErrorCode::ImageCorrupt, "the JPEG is truncated or corrupt: " + job.first_warning + " (" +
                                             std::to_string(job.corrupt_warnings) + " such problem" +
                                             (job.corrupt_warnings > 1 ? "s)" : ")"));
  return std::move(job.image);
}

}  // namespace tristim

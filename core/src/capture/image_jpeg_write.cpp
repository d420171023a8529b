// JPEG out (libjpeg-turbo, to memory): the lab's 8-bit chart photographs (tristim/lab/jpeg_writer.hpp).
//
// As in the reader (image_jpeg.cpp), libjpeg's error_exit longjmps back to the one function that
// called into it (protected_compress), which holds no C++ object; the output buffer is malloc'd by
// jpeg_mem_dest and freed here.
#include <cstdio>  // jpeglib.h needs FILE and size_t first
#include <cstdlib>
#include <csetjmp>
#include <string>

#include <jpeglib.h>

#include "tristim/error.hpp"
#include "tristim/lab/jpeg_writer.hpp"

namespace tristim {

namespace {

struct WriteJob {
  jpeg_error_mgr err{};  // first member: libjpeg's err pointer is also the job's
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {0};
};

void error_exit(j_common_ptr c) {
  WriteJob* job = reinterpret_cast<WriteJob*>(c->err);
  (*c->err->format_message)(c, job->message);
  std::longjmp(job->jump, 1);
}

void output_message(j_common_ptr) {}  // nothing reaches stderr

bool protected_compress(WriteJob* job, jpeg_compress_struct* cinfo, const std::uint8_t* rgb, int width, int height,
                        int quality, unsigned char** out, unsigned long* out_size) {
  if (setjmp(job->jump)) return false;
  jpeg_create_compress(cinfo);
  jpeg_mem_dest(cinfo, out, out_size);
  cinfo->image_width = static_cast<JDIMENSION>(width);
  cinfo->image_height = static_cast<JDIMENSION>(height);
  cinfo->input_components = 3;
  cinfo->in_color_space = JCS_RGB;
  jpeg_set_defaults(cinfo);
  jpeg_set_quality(cinfo, quality, TRUE);
  for (int c = 0; c < 3; ++c) cinfo->comp_info[c].h_samp_factor = cinfo->comp_info[c].v_samp_factor = 1;  // 4:4:4
  jpeg_start_compress(cinfo, TRUE);
  while (cinfo->next_scanline < cinfo->image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(rgb + static_cast<std::size_t>(cinfo->next_scanline) * 3 * static_cast<std::size_t>(width));
    jpeg_write_scanlines(cinfo, &row, 1);
  }
  jpeg_finish_compress(cinfo);
  return true;
}

}  // namespace

std::vector<std::uint8_t> write_jpeg_rgb8(const std::vector<std::uint8_t>& rgb, int width, int height, int quality) {
  if (width < 1 || height < 1 || width > 65500 || height > 65500 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
    throw Error(ErrorCode::InvalidArgument, "JPEG writer: " + std::to_string(rgb.size()) + " values do not make a " +
                                                std::to_string(width) + " x " + std::to_string(height) + " RGB image");
  if (quality < 1 || quality > 100)
    throw Error(ErrorCode::InvalidArgument, "JPEG quality must be 1..100, got " + std::to_string(quality));
  WriteJob job;
  jpeg_compress_struct cinfo{};
  cinfo.err = jpeg_std_error(&job.err);
  job.err.error_exit = error_exit;
  job.err.output_message = output_message;
  unsigned char* out = nullptr;
  unsigned long out_size = 0;
  const bool ok = protected_compress(&job, &cinfo, rgb.data(), width, height, quality, &out, &out_size);
  std::vector<std::uint8_t> bytes;
  if (ok) bytes.assign(out, out + out_size);
  jpeg_destroy_compress(&cinfo);
  std::free(out);
  if (!ok) throw Error(ErrorCode::InvalidArgument, std::string("JPEG writer: ") + job.message);
  return bytes;
}

}  // namespace tristim

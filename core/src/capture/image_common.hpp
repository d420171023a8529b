// What the TIFF, PNG and JPEG decoders share (private to core/src/capture/image_*.cpp): the
// RawImage they fill, with its size limit and metadata, and the store of one stored sample.
#pragma once
#include <cstdint>
#include <string>

#include "tristim/capture/image.hpp"

namespace tristim::image_detail {

/// A width × height image of `channels` (1 = grey, 3 = RGB) stored samples of `bits` (8 or 16)
/// from the decoder `format`: metadata filled (capture/image.hpp), rgb and saturated allocated.
/// Errors: ImageCorrupt (a zero side), LimitExceeded (over options.max_megapixels; checked
/// before anything is allocated).
RawImage new_image(const char* format, std::uint64_t width, std::uint64_t height, int channels,
                   int bits, const ImageDecodeOptions& options);

/// new_image without the pixels (rgb and saturated empty; same checks, same metadata), for a
/// decoder that first sees whether the data decodes at all: a file refused at its first strip
/// costs no image-sized allocation (up to ~2 GB at the 160 MP limit). allocate_pixels() then
/// sizes rgb and saturated as new_image does.
RawImage new_image_header(const char* format, std::uint64_t width, std::uint64_t height, int channels,
                          int bits, const ImageDecodeOptions& options);
void allocate_pixels(RawImage& img);

/// Sets sample `channel` (0..2; -1 = all three, for grey) of pixel (x, y) to the stored value v
/// and marks it saturated when v is the full scale.
inline void store(RawImage& img, std::size_t x, std::size_t y, int channel, std::uint32_t v,
                  std::uint32_t full_scale) {
  const std::size_t k = y * static_cast<std::size_t>(img.width) + x;
  float* px = &img.rgb[k * 3];
  const float f = static_cast<float>(v);
  const bool clipped = v >= full_scale;
  if (channel < 0) {
    px[0] = px[1] = px[2] = f;
    if (clipped) img.saturated[k] = 7;
  } else {
    px[channel] = f;
    if (clipped) img.saturated[k] |= static_cast<std::uint8_t>(1u << channel);
  }
}

/// Stores one decoded row of interleaved samples (`channels` per pixel, 1 or 3; 8-bit bytes or
/// native-endian 16-bit words) as row y.
void store_row(RawImage& img, int y, const void* samples, int channels, int bits);

/// Appends one item to meta.declared_colour (';'-separated).
void declare(RawMetadata& meta, const std::string& item);

}  // namespace tristim::image_detail

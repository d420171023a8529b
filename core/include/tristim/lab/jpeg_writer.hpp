// tristim — a baseline JPEG writer (libjpeg-turbo, in memory): the colorimetry lab's chart
// photographs through an OECF as 8-bit files (lab/render.hpp), as a phone or a camera's JPEG
// engine would store them. Implemented beside the reader, core/src/capture/image_jpeg_write.cpp.
#pragma once
#include <cstdint>
#include <vector>

namespace tristim {

/// A baseline JFIF file of width×height interleaved 8-bit R, G, B values (row-major), YCbCr without
/// chroma subsampling (4:4:4, so a flat patch keeps its colour to the quantisation's rounding), at
/// `quality` (1..100, libjpeg's scale of the standard tables). Error(InvalidArgument) if sizes do not
/// match or the quality is out of range.
std::vector<std::uint8_t> write_jpeg_rgb8(const std::vector<std::uint8_t>& rgb, int width, int height, int quality = 95);

}  // namespace tristim

// RAW open/decode from memory (capture/raw.hpp), with LibRaw compiled from its Debian source with
// the same sanitizers as the core (top-level CMakeLists.txt, TRISTIM_FUZZ): the linear decode,
// its metadata and the display preview of whatever LibRaw accepts. Seeds: corpus/raw/, tiny DNGs
// written by tests/support/dng_writer (tristim_make_test_images --fuzz-seeds).
#include "fuzz_support.hpp"
#include "tristim/capture/raw.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tristim::DecodeOptions options;
  options.max_megapixels = 1;  // keep each run small (as fuzz_image): bigger claims must still be refused early
  // decode_raw only: inspect_raw is the same open_buffer without the unpack, and every LibRaw
  // object (several MB, fresh pages from ASan's allocator each time) is what bounds the speed.
  try {
    const tristim::RawImage image = tristim::decode_raw(data, size, options);
    tristim::metadata_to_json(image.meta);
    tristim::render_preview(image, 64);
    tristim::linear_data_hash(image);
  } catch (const tristim::Error&) {
  }
  return 0;
}

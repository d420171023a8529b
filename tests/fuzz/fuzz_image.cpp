// libFuzzer targets for the image decoders (capture/image.hpp), one per parser: this file is
// compiled three times with TRISTIM_FUZZ_FORMAT = 1 (TIFF), 2 (PNG), 3 (JPEG) -> fuzz_tiff,
// fuzz_png, fuzz_jpeg. A coded tristim::Error is the expected answer to bad bytes; anything else
// (a crash, a sanitizer report, another exception, a hang) is a finding. Seeds: corpus/<format>/.
#include <cstddef>
#include <cstdint>

#include "tristim/capture/image.hpp"
#include "tristim/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tristim::ImageDecodeOptions options;
  options.max_megapixels = 4;  // keep each run small: big claims must still be refused early
  try {
#if TRISTIM_FUZZ_FORMAT == 1
    tristim::decode_tiff(data, size, options);
#elif TRISTIM_FUZZ_FORMAT == 2
    tristim::decode_png(data, size, options);
#elif TRISTIM_FUZZ_FORMAT == 3
    tristim::decode_jpeg(data, size, options);
#else
#error "TRISTIM_FUZZ_FORMAT: 1 TIFF, 2 PNG, 3 JPEG"
#endif
  } catch (const tristim::Error&) {
  }
  return 0;
}

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
  // 1 MP (was 4): a header's claimed size, not the file, sets the work of one input (the image is
  // allocated and zeroed, then every row stored, even for 500 bytes of data), so this cap sets the
  // fuzzer's speed (fuzz_tiff ~4x faster than at 4 MP). Nothing is lost: a larger claim still
  // runs the refusal (LIMIT_EXCEEDED), and no code path depends on the size beyond it.
  // OSS-Fuzz's libjpeg-turbo fuzzer skips images over 1024 x 1024 for the same reason.
  options.max_megapixels = 1;
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

// CSV / CGATS / spectral CSV reader (io/patch_files.hpp). The first byte picks the file name, so
// both the content sniffing and the extension tie-break are reached.
#include "fuzz_support.hpp"
#include "tristim/io/patch_files.hpp"

TRISTIM_FUZZ_TARGET({
  static const char* names[] = {"in.csv", "in.ti3", "in.cie", "in.txt"};
  const char* name = names[input.empty() ? 0 : static_cast<unsigned char>(input[0]) % 4];
  tristim::read_patch_file(input, name);
  tristim::read_cgats(input, name);
})

// CSV / CGATS / spectral CSV reader (io/patch_files.hpp), and the two readers built on it for the
// sensitivities estimate's own files (read_illuminant_csv, read_reflectance_file). The first byte
// picks the file name, so both the content sniffing and the extension tie-break are reached; each
// reader runs whether or not the one before it refused the input.
#include "fuzz_support.hpp"
#include "tristim/io/patch_files.hpp"

namespace {
template <class F>
void each(F&& f) {
  try {
    f();
  } catch (const tristim::Error&) {
  }
}
}  // namespace

TRISTIM_FUZZ_TARGET({
  static const char* names[] = {"in.csv", "in.ti3", "in.cie", "in.txt"};
  const char* name = names[input.empty() ? 0 : static_cast<unsigned char>(input[0]) % 4];
  each([&] { tristim::read_patch_file(input, name); });
  each([&] { tristim::read_cgats(input, name); });
  each([&] { tristim::read_illuminant_csv(input, name); });
  each([&] { tristim::read_reflectance_file(input, name); });
})

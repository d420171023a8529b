// Shared by the libFuzzer targets: a coded tristim::Error is the expected way to refuse input;
// anything else (another exception, a crash, a sanitizer report) is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "tristim/error.hpp"

// Variadic: a body with top-level commas (an array initialiser) is one argument.
#define TRISTIM_FUZZ_TARGET(...)                                                   \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    const std::string input(reinterpret_cast<const char*>(data), size);           \
    try {                                                                          \
      __VA_ARGS__;                                                                 \
    } catch (const tristim::Error&) {                                              \
    }                                                                              \
    return 0;                                                                      \
  }

namespace tristim::fuzz {

/// The round trip a writer owes its reader: what `write` makes of `read(input)` must read again
/// (a coded refusal of the writer's own text is a finding, not a refusal) and write to the same
/// text. A coded error from `read(input)` itself is the input refused. Returns what was read.
template <class Read, class Write>
auto round_trip(const std::string& input, Read read, Write write) {
  auto value = read(input);
  const std::string text = write(value);
  std::string again;
  try {
    again = write(read(text));
  } catch (const tristim::Error&) {
    std::abort();
  }
  if (again != text) std::abort();
  return value;
}

}  // namespace tristim::fuzz

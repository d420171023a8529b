// Shared by the libFuzzer targets: a coded tristim::Error is the expected way to refuse input;
// anything else (another exception, a crash, a sanitizer report) is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
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

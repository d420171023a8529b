// Shared by the libFuzzer targets: a coded tristim::Error is the expected way to refuse input;
// anything else (another exception, a crash, a sanitizer report) is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "tristim/error.hpp"

#define TRISTIM_FUZZ_TARGET(body)                                                  \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    const std::string input(reinterpret_cast<const char*>(data), size);           \
    try {                                                                          \
      body;                                                                        \
    } catch (const tristim::Error&) {                                              \
    }                                                                              \
    return 0;                                                                      \
  }

// Helpers shared by the Catch2 suite (native and wasm).
#pragma once
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>

#include "tristim/error.hpp"

namespace tristim::test {

/// Folder of ../shared/data (env TRISTIM_SHARED_DATA overrides the configured path).
inline std::string shared_data_dir() {
  if (const char* env = std::getenv("TRISTIM_SHARED_DATA")) return env;
  return TRISTIM_SHARED_DATA_DIR;
}

/// Reads a file of ../shared/data. A missing file fails the test with a message saying that
/// this test needs the project's shared data and where it looked.
inline std::string read_shared(const std::string& relative) {
  const std::string path = shared_data_dir() + "/" + relative;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    FAIL("this test needs the project's shared data, not found at '" << path
         << "' (set TRISTIM_SHARED_DATA to the shared/data folder)");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Reads a file of this repository (e.g. "examples/...").
inline std::string read_repo(const std::string& relative) {
  const std::string path = std::string(TRISTIM_SOURCE_DIR) + "/" + relative;
  std::ifstream in(path, std::ios::binary);
  if (!in) FAIL("repository file not found: '" << path << "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The ErrorCode that f() throws; fails the test if it throws none.
inline ErrorCode code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    INFO(e.what());
    return e.code();
  }
  FAIL("expected a coded error");
  return ErrorCode::Internal;
}

/// Checks that f() throws tristim::Error with `code` (compared by name, so a failure prints both).
inline void require_code(const std::function<void()>& f, ErrorCode code) {
  CHECK(std::string(error_code_name(code_of(f))) == error_code_name(code));
}

/// FNV-1a 64 over the bits of doubles, one 64-bit word at a time: the pinned hashes of the
/// cross-build tests (the same in every build exactly when the values are).
struct BitHash {
  std::uint64_t value = 1469598103934665603ULL;
  void add(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    value = (value ^ b) * 1099511628211ULL;
  }
  /// As it is written in the tests: "0x…ULL".
  std::string text() const {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%016llxULL", static_cast<unsigned long long>(value));
    return buf;
  }
};

}  // namespace tristim::test

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

#include "test_files.hpp"
#include "tristim/error.hpp"

namespace tristim::test {

/// Full path of a file the tests read: repository-relative ("tests/data/…", "core/data/…",
/// "examples/…"), or absolute for a file a Debian package installs (namespace debian).
inline std::string test_file_path(const std::string& path) { return test_file_path(TRISTIM_SOURCE_DIR, path); }

/// Reads a file the tests need (see test_file_path). A missing file fails the test with a message
/// naming it; nothing is skipped.
inline std::string read_test_file(const std::string& path) {
  const std::string full = test_file_path(path);
  std::ifstream in(full, std::ios::binary);
  if (!in) {
    if (!path.empty() && path[0] == '/')
      FAIL("this test reads '" << full << "', which a Debian package installs: run scripts/install-deps.sh "
                               "(tests/data/SOURCES.md names the package)");
    FAIL("this test reads '" << full << "', a file of the repository, which is missing");
  }
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

// Helpers shared by the Catch2 suite (native and wasm).
#pragma once
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace tristim::test

// Text edits for the reader tests: a known-good file with one piece changed (Catch2; native and wasm).
#pragma once
#include <string>

#include "test_support.hpp"

namespace tristim::test {

/// `text` with the first `from` replaced by `to`; fails the test if `from` is not in it (so an
/// edit that no longer applies cannot pass as a refusal of the unchanged text).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace tristim::test

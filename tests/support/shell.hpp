// Native-only helpers for the Catch2 cases that drive the CLI as a user would: whole files in and
// out, and a shell command's output with its exit status checked.
#pragma once
#ifndef __EMSCRIPTEN__
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.hpp"

namespace tristim::test {

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void spit(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

/// Runs `cmd` (a shell command line, redirections included); its stdout. With `must_succeed` a
/// non-zero exit fails the test, showing the command, `detail` (e.g. its stderr) and the output.
inline std::string run_shell(const std::string& cmd, bool must_succeed = true,
                             const std::function<std::string()>& detail = {}) {
  FILE* f = popen(cmd.c_str(), "r");
  REQUIRE(f != nullptr);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  const int rc = pclose(f);
  INFO("command: " << cmd << (detail ? "\n" + detail() : std::string()) << "\noutput: " << out.substr(0, 3000));
  if (must_succeed) REQUIRE(rc == 0);
  return out;
}

}  // namespace tristim::test
#endif

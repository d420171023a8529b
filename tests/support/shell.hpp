// Native-only helpers for the Catch2 cases that drive the CLI as a user would: whole files in and
// out, and a shell command's output with its exit status checked.
#pragma once
#ifndef __EMSCRIPTEN__
#include <cstdio>
#include <cstdlib>
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

/// A fresh folder for one test's files (`d`, ending in '/'), in the working directory (the build's
/// test folder), removed with its contents when the test ends, also when a REQUIRE stops it.
struct ScratchDir {
  std::string d;
  explicit ScratchDir(const std::string& name) {
    std::string folder = "tristim_" + name + "_XXXXXX";
    REQUIRE(mkdtemp(folder.data()) != nullptr);
    d = folder + "/";
  }
  ~ScratchDir() { std::system(("rm -rf '" + d + "'").c_str()); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

}  // namespace tristim::test
#endif

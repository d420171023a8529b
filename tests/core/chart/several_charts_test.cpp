// Several charts in one fit (issue 48): `tristim fit` and `tristim compare` with one --rgb/--xyz
// pair per chart train on the union of their patches (ids kept per chart as "k:id"): the profile
// equals, to the bit, the one fitted on a single table holding the same rows, and the figures are
// given per chart as well as overall. Drives the CLI as a user would (native only).
#ifndef __EMSCRIPTEN__
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <stdlib.h>

#include "shell.hpp"
#include "test_support.hpp"

using namespace tristim::test;

namespace {

// Each line of a CSV after the header with "k:" before its patch id.
std::string numbered(const std::string& csv, int k, bool header) {
  std::istringstream in(csv);
  std::string line, out;
  std::getline(in, line);
  if (header) out += line + "\n";
  while (std::getline(in, line))
    if (!line.empty()) out += std::to_string(k) + ":" + line + "\n";
  return out;
}

// The profile without the digest of the --xyz file's bytes (one file against two).
std::string without_file_digest(const std::string& profile) {
  std::istringstream in(profile);
  std::string line, out;
  while (std::getline(in, line))
    if (line.find("\"data_digest\"") == std::string::npos) out += line + "\n";
  return out;
}

}  // namespace

TEST_CASE("two charts in one fit: the fit of their concatenated tables, to the bit, with figures per chart",
          "[several-charts]") {
  const tristim::test::ScratchDir scratch("charts");
  const std::string& d = scratch.d;
  const std::string cli = TRISTIM_CLI;
  const std::string cam = " --camera Canon_EOS_5D_Mark_II --illuminant D50 --noise 0.002";
  run_shell(cli + " simulate" + cam + " --reflectances cc24 --seed 3 > " + d + "a.csv");
  run_shell(cli + " simulate" + cam + " --reflectances sg140 --seed 4 > " + d + "b.csv");
  run_shell(cli + " reference --chart cc24 --illuminant D50 > " + d + "ra.csv");
  run_shell(cli + " reference --chart sg140 --illuminant D50 > " + d + "rb.csv");
  spit(d + "ab.csv", numbered(slurp(d + "a.csv"), 1, true) + numbered(slurp(d + "b.csv"), 2, false));
  spit(d + "rab.csv", numbered(slurp(d + "ra.csv"), 1, true) + numbered(slurp(d + "rb.csv"), 2, false));
  for (const std::string model : {"Finlayson2015-2 --objective ls", "matrix-3x3 --objective de2000"}) {
    INFO(model);
    const std::string two = run_shell(cli + " fit --rgb " + d + "a.csv --rgb " + d + "b.csv --xyz " + d + "ra.csv --xyz " +
                                      d + "rb.csv --model " + model + " --out " + d + "two.json 2>&1");
    run_shell(cli + " fit --rgb " + d + "ab.csv --xyz " + d + "rab.csv --model " + model + " --out " + d + "one.json 2>&1");
    const std::string a = without_file_digest(slurp(d + "two.json")), b = without_file_digest(slurp(d + "one.json"));
    REQUIRE(a.size() > 1000);
    CHECK(a == b);
    CHECK(a.find("\"patches\": 164") != std::string::npos);
    // Leave-one-out per chart and overall.
    CHECK(two.find("leave-one-out mean dE00") != std::string::npos);
    CHECK(two.find("chart 1 (" + d + "a.csv): 24 patches, training mean/max dE00 ") != std::string::npos);
    CHECK(two.find("chart 2 (" + d + "b.csv): 140 patches") != std::string::npos);
    CHECK(two.find("leave-one-out mean/max dE00") != std::string::npos);
  }
  const std::string table = run_shell(cli + " compare --rgb " + d + "a.csv --rgb " + d + "b.csv --xyz " + d + "ra.csv --xyz " +
                                      d + "rb.csv --objectives ls --models matrix-3x3,Finlayson2015-2");
  CHECK(table.find("# 164 patches") == 0);
  CHECK(table.find("# per chart, ") != std::string::npos);
  CHECK(table.find("# chart 2 (" + d + "b.csv): 140 patches") != std::string::npos);
  // One --xyz short: refused, naming the options.
  const std::string refused = run_shell(cli + " fit --rgb " + d + "a.csv --rgb " + d + "b.csv --xyz " + d +
                                            "ra.csv --model matrix-3x3 2>&1; echo rc=$?", false);
  CHECK(refused.find("INVALID_ARGUMENT: --rgb and --xyz: 2 camera tables but 1 reference tables") != std::string::npos);
  CHECK(refused.find("rc=1") != std::string::npos);
}
#endif

// `tristim fit --rgb a.csv --xyz r.csv` when the RGB table lacks some of the reference's patches (a
// chart cut by the frame: `tristim sample` writes only the visible ones): the fit pairs by id and
// trains on the patches both hold, and says on stderr which reference patches had no RGB. RGB ids
// the reference lacks are still refused. Native only: the CLI is driven as a user would.
#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
#include <unistd.h>

#include <cstdlib>
#include <sstream>
#include <string>

#include "shell.hpp"
#include "test_support.hpp"

using namespace tristim;
using namespace tristim::test;

namespace {
struct Dir : ScratchDir {
  Dir() : ScratchDir("fit_cut_chart") {
    const std::string cli = TRISTIM_CLI;
    run_shell(cli + " simulate --camera Nikon_D850 --reflectances cc24 --illuminant D65 > " + d + "rgb.csv");
    run_shell(cli + " reference --chart cc24 --illuminant D65 > " + d + "xyz.csv");
  }
  /// `from` without the rows of the patches `ids` (a header line, then one row per patch).
  void drop(const std::string& from, const std::string& to, const std::vector<std::string>& ids) const {
    std::istringstream in(slurp(d + from));
    std::string out, line;
    while (std::getline(in, line)) {
      bool keep = true;
      for (const auto& id : ids) keep = keep && line.compare(0, id.size() + 1, id + ",") != 0;
      if (keep) out += line + "\n";
    }
    spit(d + to, out);
  }
  /// `tristim fit` with `options`: its stdout, stderr and exit status as one text ("rc=N" last).
  std::string fit(const std::string& options, const std::string& out = "/dev/null") const {
    return run_shell(std::string(TRISTIM_CLI) + " fit " + options + " --model matrix-3x3 2>&1 >" + out + "; echo rc=$?",
                     false);
  }
  /// The file's text without its "data_digest" line (the digest of the --xyz file's bytes).
  std::string without_digest(const std::string& name) const {
    std::istringstream in(slurp(d + name));
    std::string out, line;
    while (std::getline(in, line))
      if (line.find("\"data_digest\"") == std::string::npos) out += line + "\n";
    return out;
  }
};
}  // namespace

TEST_CASE("cli: fit pairs a cut chart's RGB with the whole reference by id", "[characterisation][cli][patches]") {
  const Dir t;
  const std::string& d = t.d;
  t.drop("rgb.csv", "rgb_cut.csv", {"A1", "B3", "D6"});
  t.drop("xyz.csv", "xyz_cut.csv", {"A1", "B3", "D6"});
  // The whole reference: the same profile, bit for bit, as the reference cut to the same patches.
  const std::string said = t.fit("--rgb " + d + "rgb_cut.csv --xyz " + d + "xyz.csv", d + "whole.json");
  CHECK(said == "tristim fit: 3 reference patches have no RGB (A1, B3, D6): fitted on the 21 others\nrc=0\n");
  CHECK(t.fit("--rgb " + d + "rgb_cut.csv --xyz " + d + "xyz_cut.csv", d + "cut.json") == "rc=0\n");
  CHECK(slurp(d + "whole.json").find("\"A1\"") == std::string::npos);  // no row of a patch it has no RGB for
  CHECK(t.without_digest("whole.json") == t.without_digest("cut.json"));
  CHECK(t.without_digest("whole.json").size() > 1000);
  // Every patch of both: no line about missing patches, and a different fit (24 patches, not 21).
  CHECK(t.fit("--rgb " + d + "rgb.csv --xyz " + d + "xyz.csv", d + "all.json") == "rc=0\n");
  CHECK(t.without_digest("all.json") != t.without_digest("whole.json"));
  CHECK(slurp(d + "all.json").find("\"A1\"") != std::string::npos);
}

TEST_CASE("cli: fit still refuses RGB patches the reference lacks, naming both files",
          "[characterisation][cli][patches]") {
  const Dir t;
  const std::string& d = t.d;
  // The whole RGB with a cut reference.
  t.drop("xyz.csv", "xyz_cut.csv", {"A1", "B3"});
  std::string said = t.fit("--rgb " + d + "rgb.csv --xyz " + d + "xyz_cut.csv");
  CHECK(said.find("PATCH_MISMATCH") != std::string::npos);
  CHECK(said.find("'A1' of " + d + "rgb.csv is not in " + d + "xyz_cut.csv") != std::string::npos);
  CHECK(said.find("rc=0") == std::string::npos);
  // A cut RGB holding one id the reference does not know.
  spit(d + "rgb_odd.csv", "patch,R,G,B\nA2,0.2,0.3,0.2\nZ9,0.1,0.1,0.1\nC3,0.05,0.1,0.2\nD1,0.6,0.6,0.6\n");
  said = t.fit("--rgb " + d + "rgb_odd.csv --xyz " + d + "xyz.csv");
  CHECK(said.find("PATCH_MISMATCH: patch 'Z9' of " + d + "rgb_odd.csv is not in " + d + "xyz.csv") !=
        std::string::npos);
  CHECK(said.find("rc=0") == std::string::npos);
  // No id in common.
  spit(d + "rgb_none.csv", "patch,R,G,B\nQ1,0.2,0.3,0.2\nQ2,0.1,0.1,0.1\nQ3,0.05,0.1,0.2\nQ4,0.6,0.6,0.6\n");
  said = t.fit("--rgb " + d + "rgb_none.csv --xyz " + d + "xyz.csv");
  CHECK(said.find("PATCH_MISMATCH: " + d + "rgb_none.csv and " + d + "xyz.csv: no patch id is shared") !=
        std::string::npos);
  CHECK(said.find("rc=0") == std::string::npos);
}
TEST_CASE("cli: compare takes a cut chart for training and held out, as fit and evaluate do",
          "[characterisation][cli][patches]") {
  const Dir t;
  const std::string& d = t.d;
  t.drop("rgb.csv", "rgb_cut.csv", {"A1", "B3", "D6"});
  t.drop("rgb.csv", "test_cut.csv", {"A2", "C4"});
  const std::string cli = TRISTIM_CLI;
  const std::string said =
      run_shell(cli + " compare --rgb " + d + "rgb_cut.csv --xyz " + d + "xyz.csv --test-rgb " + d + "test_cut.csv --test-xyz " +
                    d + "xyz.csv --models matrix-3x3 --objectives ls --json 2>" + d + "err.txt >" + d +
                    "out.json; echo rc=$?",
                false);
  CHECK(said == "rc=0\n");
  CHECK(slurp(d + "err.txt") ==
        "tristim compare: 3 reference patches have no RGB (A1, B3, D6): compared on the 21 others\n"
        "tristim compare: 2 reference patches have no RGB (A2, C4): held out on the 22 others\n");
  const std::string out = slurp(d + "out.json");
  CHECK(out.find("\"patches\": 21") != std::string::npos);
  CHECK(out.find("\"transfer\"") != std::string::npos);
  // An RGB id the reference lacks is still refused.
  spit(d + "rgb_odd.csv", "patch,R,G,B\nA2,0.2,0.3,0.2\nZ9,0.1,0.1,0.1\nC3,0.05,0.1,0.2\nD1,0.6,0.6,0.6\n");
  const std::string odd = run_shell(cli + " compare --rgb " + d + "rgb.csv --xyz " + d + "xyz.csv --test-rgb " + d +
                                        "rgb_odd.csv --test-xyz " + d + "xyz.csv --models matrix-3x3 2>&1; echo rc=$?",
                                    false);
  CHECK(odd.find("PATCH_MISMATCH") != std::string::npos);
  CHECK(odd.find("rc=0") == std::string::npos);
}
#endif

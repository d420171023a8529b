// Every command that writes patch rows writes the ids as the input spelled them ("Q001" stays
// "Q001", a file's "A01" stays "A01"), while pairing still matches "A01" with "A1". Native only: the
// CLI is driven as a user would (TRISTIM_CLI), on tiny files written here; the absolute mode's
// per-point read-out needs RAW frames and is checked by native:cli:absolute-point-ids.
#ifndef __EMSCRIPTEN__
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "shell.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/io/json.hpp"
#include "tristim/io/patch_files.hpp"

using namespace tristim;
using Ids = std::vector<std::string>;

namespace {

struct Dir {
  // One folder per process (ctest runs test cases in parallel), removed at exit.
  std::string path = "tristim_patch_ids_" + std::to_string(getpid());
  Dir() { std::system(("mkdir -p " + path).c_str()); }
  ~Dir() { std::system(("rm -rf " + path).c_str()); }
  std::string operator/(const std::string& name) const { return path + "/" + name; }
};

using test::slurp;
using test::spit;

/// Runs the CLI with `args`; its stdout. Fails the test on a non-zero exit, showing stderr.
std::string cli(const std::string& args, const Dir& d) {
  const std::string err = d / "stderr.txt";
  return test::run_shell(std::string(TRISTIM_CLI) + " " + args + " 2>" + err, true,
                         [&] { return "stderr: " + slurp(err); });
}

/// The first cell of every data row of a CSV (lines starting with '#' skipped).
Ids first_column(const std::string& csv) {
  Ids ids;
  std::istringstream in(csv);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) { header = false; continue; }
    ids.push_back(line.substr(0, line.find(',')));
  }
  return ids;
}

/// The column names after the first of a spectral CSV's header.
Ids spectral_names(const std::string& csv) {
  Ids names;
  std::istringstream line(csv.substr(0, csv.find('\n')));
  std::string cell;
  std::getline(line, cell, ',');
  while (std::getline(line, cell, ',')) names.push_back(cell);
  return names;
}

/// The "patch" (or "id") member of each object of a JSON array.
Ids patch_members(const json::Value& a, const char* key = "patch") {
  Ids ids;
  for (const auto& o : a.as_array()) ids.push_back(o.at(key).as_string());
  return ids;
}

Ids qids(size_t n) {
  Ids ids;
  char buf[16];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "Q%03zu", i + 1);
    ids.push_back(buf);
  }
  return ids;
}

/// The Passport's patches through a virtual camera, written with the ids Q001..Q024 (camera RGB) and
/// q1..q24 (reference XYZ): the same patches in both, spelled differently.
struct Files {
  Dir d;
  std::string rgb = d / "rgb.csv", xyz = d / "xyz.csv", spectra, rgb_a01 = d / "rgb_a01.csv";
  Ids q, a01;  // Q001.. ; A01..D06
  Files() {
    spectra = test::test_file_path("core/data/charts/colorchecker24_after_nov2014_reflectance_380-730_10nm.csv");
    const std::string sim = cli("simulate --camera Nikon_D850 --reflectances cc24 --illuminant D65 --precision 17", d);
    const std::string ref = cli("reference --chart cc24 --illuminant D50 --precision 17", d);
    const PatchTable s = read_patch_file(sim, "sim.csv"), r = read_patch_file(ref, "ref.csv");
    REQUIRE(s.ids.size() == 24);
    REQUIRE(r.ids == s.ids);
    q = qids(24);
    std::ostringstream o, x, a;
    o.precision(17);
    x.precision(17);
    a.precision(17);
    o << "patch,R,G,B\n";
    x << "patch,X,Y,Z\n";
    a << "SAMPLE_LOC,R,G,B\n";
    for (size_t i = 0; i < 24; ++i) {
      o << q[i] << ',' << s.RGB[i][0] << ',' << s.RGB[i][1] << ',' << s.RGB[i][2] << '\n';
      x << 'q' << i + 1 << ',' << r.XYZ[i][0] << ',' << r.XYZ[i][1] << ',' << r.XYZ[i][2] << '\n';
      const std::string id = s.ids[i].substr(0, 1) + "0" + s.ids[i].substr(1);  // A1 -> A01
      a01.push_back(id);
      a << id << ',' << s.RGB[i][0] << ',' << s.RGB[i][1] << ',' << s.RGB[i][2] << '\n';
    }
    spit(rgb, o.str());
    spit(xyz, x.str());
    spit(rgb_a01, a.str());
  }
};

const Files& files() {
  static Files f;
  return f;
}

}  // namespace

TEST_CASE("cli: linearise writes the RGB file's ids", "[cli][ids]") {
  const Files& f = files();
  CHECK(first_column(cli("linearise --method gamma --rgb " + f.rgb, f.d)) == f.q);
  cli("linearise --method gamma --rgb " + f.rgb + " --out " + (f.d / "lin.csv"), f.d);
  CHECK(first_column(slurp(f.d / "lin.csv")) == f.q);
  // The greys a fit used, in --json, as spelled in the file.
  const json::Value j = json::parse(cli("linearise --method grey-polynomial --rgb " + f.rgb + " --xyz " + f.xyz + " --json", f.d));
  const json::Value& greys = j.at("linearisation").at("greys");
  REQUIRE(greys.size() > 0);
  for (const auto& g : greys.as_array()) CHECK(g.as_string().rfind("Q0", 0) == 0);
}

TEST_CASE("cli: fit and evaluate write the RGB file's ids, pairing Q001 with q1", "[cli][ids]") {
  const Files& f = files();
  const std::string profile = f.d / "p.json";
  cli("fit --rgb " + f.rgb + " --xyz " + f.xyz + " --model matrix-3x3 --white Q019 --out " + profile + " --csv " +
          (f.d / "fit.csv"),
      f.d);
  CHECK(first_column(slurp(f.d / "fit.csv")) == f.q);
  const json::Value e = json::parse(cli("evaluate --profile " + profile + " --rgb " + f.rgb + " --xyz " + f.xyz + " --csv " +
                                            (f.d / "evaluate.csv"),
                                        f.d));
  CHECK(first_column(slurp(f.d / "evaluate.csv")) == f.q);
  Ids ids;
  for (const auto& v : e.at("metrics").at("patches").at("ids").as_array()) ids.push_back(v.as_string());
  CHECK(ids == f.q);
  // The same data under other spellings of the same ids: the same training data.
  CHECK(e.at("same_data_as_training").as_bool());
}

TEST_CASE("cli: fit --recipe writes the RGB file's A01, paired with the chart's A1", "[cli][ids][recipe]") {
  const Files& f = files();
  const std::string recipe = test::test_file_path("examples/recipes/passport-rootpoly2-psm.json");
  cli("fit --recipe " + recipe + " --rgb " + f.rgb_a01 + " --out " + (f.d / "r.json") + " --csv " + (f.d / "r.csv"), f.d);
  CHECK(first_column(slurp(f.d / "r.csv")) == f.a01);
}

TEST_CASE("cli: spectral fit and apply write the RGB file's ids", "[cli][ids]") {
  // The RGB file's A01 pairs with the chart's spectra named A1; the outputs say A01.
  const Files& f = files();
  const std::string model = f.d / "w.json";
  const json::Value fit =
      json::parse(cli("spectral fit --rgb " + f.rgb_a01 + " --reflectances cc24 --csv " + (f.d / "est.csv"), f.d));
  CHECK(spectral_names(slurp(f.d / "est.csv")) == f.a01);
  CHECK(patch_members(fit.at("training").at("patches")) == f.a01);
  cli("spectral fit --rgb " + f.rgb_a01 + " --reflectances cc24 --out " + model, f.d);
  // apply: any RGB file, its own ids (no reflectances needed).
  CHECK(spectral_names(cli("spectral apply " + model + " --rgb " + f.rgb, f.d)) == f.q);
  const json::Value ev = json::parse(cli("spectral apply " + model + " --rgb " + f.rgb_a01 + " --reflectances cc24 --json", f.d));
  CHECK(patch_members(ev.at("patches")) == f.a01);
}

TEST_CASE("cli: simulate and surface fit write a spectral file's own column names", "[cli][ids]") {
  const Files& f = files();
  // The built-in Classic file names its columns A01..D06; the chart id gives A1..D6.
  CHECK(first_column(cli("simulate --camera Nikon_D850 --reflectances " + f.spectra, f.d)) == f.a01);
  const Ids chart = first_column(cli("simulate --camera Nikon_D850 --reflectances cc24", f.d));
  CHECK(chart.front() == "A1");
  CHECK(first_column(cli("surface fit --from " + f.spectra + " --to " + f.spectra + " --method scaler", f.d)) == f.a01);
  const json::Value j = json::parse(cli("surface fit --from " + f.spectra + " --to " + f.spectra + " --method offset --json", f.d));
  CHECK(patch_members(j.at("patches")) == f.a01);
  // linearise pairs the RGB file's A01 with the spectral file's A01 (and would with A1).
  CHECK(first_column(cli("linearise --method Shen2008 --rgb " + f.rgb_a01 + " --reflectances " + f.spectra, f.d)) == f.a01);
}

TEST_CASE("cli: difference copies the rows' ids as written", "[cli][ids]") {
  const Files& f = files();
  spit(f.d / "pairs.csv", "pair,L1,a1,b1,L2,a2,b2\nQ001,50,2.6772,-79.7751,50,0,-82.7485\n\"x, 007\",50,0,0,51,0,0\n");
  const std::string out = cli("difference --in " + (f.d / "pairs.csv"), f.d);
  CHECK(out.find("\nQ001,50,") != std::string::npos);
  CHECK(out.find("\n\"x, 007\",50,") != std::string::npos);
}

TEST_CASE("cli: sample writes the chart layout's ids (no user ids to keep)", "[cli][ids]") {
  const Files& f = files();
  const std::string dng = test::test_file_path("examples/web/passport.dng");
  const Ids ids = first_column(cli("sample " + dng + " --chart passport --corners 335,291,649,285,649,486,328,488", f.d));
  CHECK(ids == reference_chart("passport", "D50").ids);
}
#endif

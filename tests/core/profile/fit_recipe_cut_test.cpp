// `tristim fit --recipe r.json --raw cut.dng` on a chart cut by the frame (issue 48), driven as a
// user would: a ColorChecker rendered by the lab (lab/render.hpp, no noise) with its sensor rows
// below the chart's second row cut off, and a recipe whose corners put rows C and D outside the
// image. The recipe path samples the chart as the page does (SampleOptions::partial): the 12
// patches inside are sampled (their planted camera RGB recovered), the 12 outside named on stderr
// and left out (and listed in the profile's recipe, sampling.missing), and the profile equals `tristim fit --rgb --xyz cc24` on the planted RGB of the 12
// patches inside; a share link of it and its project file (sampled again from the DNG) reproduce.
// Corners that put every patch outside the image: CORNERS_OUTSIDE (native only: the CLI).
#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
#include <sstream>
#include <string>
#include <vector>

#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/io/json.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/profile/recipe.hpp"

using namespace tristim;
using namespace tristim::test;

namespace {

constexpr int kCutRows = 450;  // measurement-image rows kept: rows A and B of the chart

struct CutChart : ScratchDir {
  LabRender render;
  CutChart() : ScratchDir("fit_recipe_cut") {
    LabRenderOptions o;
    o.chart = "cc24";
    o.camera = "Nikon_D850";
    o.corners = {200, 330, 700, 330, 700, 590, 200, 590};  // rows of 65 px: A, B above row 450; C, D below
    render = render_lab_chart(o);
    // The sensor is row-major: its first 2·kCutRows rows are the frame cut at measurement row kCutRows.
    const std::vector<std::uint16_t> cut(render.sensor.begin(), render.sensor.begin() + 2L * render.width * 2 * kCutRows);
    const auto dng = write_dng(cut, 2 * render.width, 2 * kCutRows, render.dng);
    spit(d + "cut.dng", std::string(dng.begin(), dng.end()));
  }
  /// A recipe for the chart at `corners` (the reference: cc24 under D50, the CLI's default).
  std::string recipe(const std::array<double, 8>& corners) const {
    Recipe r;
    r.reference.chart = "cc24";
    r.sampling.layout.chart = "cc24";
    r.sampling.corners = corners;
    r.characterisation.model = "matrix-3x3";
    const std::string path = d + "r.json";
    spit(path, recipe_to_json(r));
    return path;
  }
};

std::vector<double> coefficients(const std::string& profile_json) {
  const json::Value profile = json::parse(profile_json);
  std::vector<double> out;
  for (const auto& row : profile.at("model").at("coefficients").as_array())
    for (const auto& v : row.as_array()) out.push_back(v.as_number());
  return out;
}

}  // namespace

TEST_CASE("fit --recipe --raw on a chart cut by the frame: the patches inside, the others named", "[recipe][cut][cli]") {
  const CutChart c;
  const std::string cli = TRISTIM_CLI, d = c.d;
  // Before issue 48's recipe step this refused the corners (CORNERS_OUTSIDE: corner 3 below the image).
  const std::string err = run_shell(cli + " fit --recipe " + c.recipe(c.render.corners) + " --raw " + d + "cut.dng --out " + d +
                                    "p.json 2>&1 >/dev/null");
  const json::Value p = json::parse(slurp(d + "p.json"));
  CHECK(p.at("training").at("patches").as_number() == 12);
  for (const char* id : {"C1", "C6", "D1", "D6"}) CHECK(err.find(std::string("left out ") + id + " (outside the frame)") != std::string::npos);
  CHECK(err.find("left out B6") == std::string::npos);
  // The profile's recipe names them too (sampling.missing, layout order), so it and its share link say
  // which patches the fit was made without.
  std::vector<std::string> missing;
  for (const auto& m : p.at("recipe").at("sampling").at("missing").as_array()) missing.push_back(m.as_string());
  CHECK(missing == std::vector<std::string>{"C1", "C2", "C3", "C4", "C5", "C6", "D1", "D2", "D3", "D4", "D5", "D6"});

  // The planted solution: the profile of the 12 patches' true camera RGB, paired with cc24's reference.
  std::ostringstream rgb;
  rgb.precision(17);
  rgb << "patch,R,G,B\n";
  for (const auto& t : c.render.patches)
    if (t.id[0] == 'A' || t.id[0] == 'B') rgb << t.id << ',' << t.rgb[0] << ',' << t.rgb[1] << ',' << t.rgb[2] << '\n';
  spit(d + "rgb.csv", rgb.str());
  run_shell(cli + " fit --rgb " + d + "rgb.csv --xyz cc24 --model matrix-3x3 --out " + d + "planted.json 2>/dev/null");
  const std::vector<double> got = coefficients(slurp(d + "p.json")), want = coefficients(slurp(d + "planted.json"));
  REQUIRE(got.size() == want.size());
  for (size_t k = 0; k < got.size(); ++k) CHECK(got[k] == Approx(want[k]).epsilon(1e-12));

  // Its share link reproduces; so does its project file, whose patches are sampled again from the DNG.
  const std::string link = run_shell(cli + " share --profile " + d + "p.json");
  CHECK(run_shell(cli + " reproduce '" + link.substr(0, link.find_last_not_of("\n") + 1) + "'").rfind("reproduced", 0) == 0);
  run_shell(cli + " share --profile " + d + "p.json --raw " + d + "cut.dng --project " + d + "cut.tristim");
  const json::Value again = json::parse(run_shell(cli + " reproduce " + d + "cut.tristim --json"));
  CHECK(again.at("verdict").as_string() == "reproduced");
  CHECK(again.at("resampled").as_bool());
}

TEST_CASE("fit --recipe --raw: corners that put every patch outside the image are refused", "[recipe][cut][cli]") {
  const CutChart c;
  const std::string out = run_shell(std::string(TRISTIM_CLI) + " fit --recipe " +
                                        c.recipe({200, 460, 700, 460, 700, 720, 200, 720}) + " --raw " + c.d + "cut.dng 2>&1; echo rc=$?",
                                    false);
  CHECK(out.find("CORNERS_OUTSIDE") != std::string::npos);
  CHECK(out.find("rc=0") == std::string::npos);
}
#endif

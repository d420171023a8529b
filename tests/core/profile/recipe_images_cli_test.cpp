// `tristim fit --recipe r.json --raw a.dng --raw b.dng` (issue 48), driven as a user would: two
// charts rendered by `tristim lab render`, fitted through a recipe with an `images` list, give the
// coefficients of `tristim fit --rgb a.csv --rgb b.csv --xyz ra.csv --xyz rb.csv` on the tables
// `tristim sample` reads from the same files, to the bit; the figures come per chart (training,
// leave-one-out, held out); bad inputs give coded one-line errors naming the image; the profile
// goes through `tristim share --profile` and `tristim reproduce` (native only).
#ifndef __EMSCRIPTEN__
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>

#include <stdlib.h>

#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/profile/recipe.hpp"

using namespace tristim;
using namespace tristim::test;

namespace {

// The text of the JSON array after "name": up to the bracket that closes it.
std::string json_array(const std::string& text, const std::string& name) {
  const auto at = text.find("\"" + name + "\"");
  REQUIRE(at != std::string::npos);
  const auto open = text.find('[', at);
  int depth = 0;
  for (size_t i = open; i < text.size(); ++i) {
    depth += text[i] == '[' ? 1 : text[i] == ']' ? -1 : 0;
    if (depth == 0) return text.substr(open, i - open + 1);
  }
  FAIL("unclosed array " << name);
  return "";
}

std::string corners_of(const std::string& truth_json) {
  std::string c = json_array(truth_json, "corners");
  std::string out;
  for (char ch : c.substr(1, c.size() - 2))
    if (ch != ' ' && ch != '\n') out += ch;
  return out;
}

// The reference table's rows in the order of the camera table's (the sampling's layout order, A1,
// B1, … for the SG): the tables' fit pairs rows in the reference's order, the recipe's in the
// sampling's, and a least-squares solve is bit-exact only for the same row order.
std::string ordered_like(const std::string& ref_csv, const std::string& rgb_csv) {
  std::map<std::string, std::string> line_of;
  std::istringstream ref(ref_csv), rgb(rgb_csv);
  std::string line, header, out;
  std::getline(ref, header);
  while (std::getline(ref, line)) line_of[line.substr(0, line.find(','))] = line;
  out = header + "\n";
  std::getline(rgb, line);
  while (std::getline(rgb, line))
    if (!line.empty()) out += line_of.at(line.substr(0, line.find(','))) + "\n";
  return out;
}

}  // namespace

TEST_CASE("fit --recipe with two images: the fit of the concatenated tables, to the bit, with figures per chart",
          "[recipe][images][cli]") {
  const tristim::test::ScratchDir scratch("images");
  const std::string& d = scratch.d;
  const std::string cli = TRISTIM_CLI;
  const std::string cam = " --camera Canon_EOS_5D_Mark_II --illuminant D65";
  const std::string ta = run_shell(cli + " lab render" + cam + " --chart cc24 --size 600x400 --out " + d + "a.dng");
  const std::string tb = run_shell(cli + " lab render" + cam + " --chart sg140 --size 600x400 --out " + d + "b.dng");
  run_shell(cli + " sample " + d + "a.dng --chart cc24 --area 0.5 --corners " + corners_of(ta) + " > " + d + "a.csv");
  run_shell(cli + " sample " + d + "b.dng --chart sg140 --area 0.5 --corners " + corners_of(tb) + " > " + d + "b.csv");
  run_shell(cli + " reference --chart cc24 --illuminant D65 > " + d + "ra.csv");
  run_shell(cli + " reference --chart sg140 --illuminant D65 > " + d + "rb.csv");
  spit(d + "rb.csv", ordered_like(slurp(d + "rb.csv"), slurp(d + "b.csv")));

  Recipe r;
  r.reference.chart = "file";
  r.characterisation.model = "Finlayson2015-2";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  for (const char* chart : {"cc24", "sg140"}) {
    RecipeImage e;
    e.name = std::string(chart) + ".dng";
    e.reference.chart = "file";
    e.sampling.layout.chart = chart;
    e.sampling.area = 0.5;
    r.images.push_back(e);
  }
  const auto set_corners = [](RecipeImage& e, const std::string& list) {
    std::string item;
    size_t k = 0;
    for (size_t i = 0; i <= list.size(); ++i) {
      if (i == list.size() || list[i] == ',') {
        e.sampling.corners[k++] = std::stod(item);
        item.clear();
      } else {
        item += list[i];
      }
    }
  };
  set_corners(r.images[0], corners_of(ta));
  set_corners(r.images[1], corners_of(tb));
  spit(d + "r.json", recipe_to_json(r));

  const std::string two = run_shell(cli + " fit --recipe " + d + "r.json --raw " + d + "a.dng --raw " + d + "b.dng --xyz " +
                                    d + "ra.csv --xyz " + d + "rb.csv --out " + d + "two.json 2>&1");
  run_shell(cli + " fit --rgb " + d + "a.csv --rgb " + d + "b.csv --xyz " + d + "ra.csv --xyz " + d +
            "rb.csv --model Finlayson2015-2 --objective ls --out " + d + "one.json 2>&1");
  const std::string p2 = slurp(d + "two.json"), p1 = slurp(d + "one.json");
  CHECK(json_array(p2, "coefficients") == json_array(p1, "coefficients"));
  CHECK(p2.find("\"patches\": 164") != std::string::npos);
  // Per chart in the text and the JSON; the profile records both images with their SHA-256.
  CHECK(two.find("tristim: chart 1 (cc24.dng): 24 patches, training mean/max dE00 ") != std::string::npos);
  CHECK(two.find("tristim: chart 2 (sg140.dng): 140 patches") != std::string::npos);
  CHECK(two.find("leave-one-out mean/max dE00") != std::string::npos);
  CHECK(two.find("held out (fitted on the other charts) mean/max dE00 ") != std::string::npos);
  CHECK(p2.find("\"charts\": [") != std::string::npos);
  CHECK(p2.find("\"held_out\": {") != std::string::npos);
  CHECK(p2.find("\"name\": \"sg140.dng\"") != std::string::npos);
  CHECK(p2.find("\"sha256\": \"" + std::string(64, '0')) == std::string::npos);
  CHECK(p2.find("\"sha256\": \"") != std::string::npos);

  // The link from the profile alone, recomputed.
  const std::string link = run_shell(cli + " share --profile " + d + "two.json --payload");
  spit(d + "link.txt", link);
  const std::string again = run_shell(cli + " reproduce \"$(cat " + d + "link.txt)\" 2>&1", false);
  CHECK(again.find("reproduced") != std::string::npos);

  // Bad inputs: coded one-line errors naming the image.
  const auto refused = [&](const std::string& args) {
    return run_shell(cli + " fit --recipe " + args + " 2>&1; echo rc=$?", false);
  };
  std::string e = refused(d + "r.json --raw " + d + "a.dng --xyz " + d + "ra.csv");
  CHECK(e.find("INVALID_ARGUMENT: the recipe lists 2 images but 1 --raw were given") != std::string::npos);
  CHECK(e.find("rc=1") != std::string::npos);
  spit(d + "bad.dng", "this is a text file, not a RAW");
  e = refused(d + "r.json --raw " + d + "a.dng --raw " + d + "bad.dng --xyz " + d + "ra.csv --xyz " + d + "rb.csv");
  CHECK(e.find("RAW_UNSUPPORTED: images[1] ('sg140.dng'): ") != std::string::npos);
  std::string text = recipe_to_json(r);
  text.replace(text.rfind("\"chart\": \"sg140\""), 16, "\"chart\": \"sg999\"");
  spit(d + "bad.json", text);
  e = refused(d + "bad.json --raw " + d + "a.dng --raw " + d + "b.dng");
  CHECK(e.find("UNKNOWN_ID: recipe: images[1] ('sg140.dng'): ") != std::string::npos);
}
#endif

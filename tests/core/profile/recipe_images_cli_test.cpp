// `tristim fit --recipe r.json --raw a.dng --raw b.dng` (issue 48), driven as a user would: two
// charts rendered by `tristim lab render`, fitted through a recipe with an `images` list, give the
// coefficients of `tristim fit --rgb a.csv --rgb b.csv --xyz ra.csv --xyz rb.csv` on the tables
// `tristim sample` reads from the same files, to the bit; the figures come per chart (training,
// leave-one-out, held out); bad inputs give coded one-line errors naming the image; the profile
// goes through `tristim share --profile` and `tristim reproduce` (native only).
#ifndef __EMSCRIPTEN__
#include <cstdlib>
#include <iomanip>
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

// Two charts in one image (issue 48): a ColorChecker left (exposure 0.3) and one right (0.2,
// slightly turned), the halves of two `lab render` TIFFs (linear, one strip) spliced into one file.
// `detect` finds both; a recipe entry with candidate "all", and a recipe naming the file twice with
// each candidate's corners, both fit the concatenation of the tables `sample` reads at those
// corners, to the bit (noise off: every patch is uniform, so its mean does not move with the
// corners' last printed digit).
TEST_CASE("fit --recipe: two charts in one image, both used (candidate \"all\", or the file twice), to the bit",
          "[recipe][images][cli]") {
  const tristim::test::ScratchDir scratch("one-image");
  const std::string& d = scratch.d;
  const std::string cli = TRISTIM_CLI;
  const std::string render = cli + " lab render --camera Canon_EOS_5D_Mark_II --illuminant D65 --chart cc24 --size 900x600 --oecf linear";
  run_shell(render + " --exposure 0.3 --corners 40,150,400,150,400,390,40,390 --out " + d + "a.tiff");
  run_shell(render + " --exposure 0.2 --corners 480,180,860,160,870,420,490,430 --out " + d + "b.tiff");
  std::string two = slurp(d + "a.tiff");
  const std::string b = slurp(d + "b.tiff");
  REQUIRE(two.size() == b.size());
  const size_t row = 900 * 6, strip = two.size() - 600 * row;  // lab render writes the one strip last
  for (size_t y = 0; y < 600; ++y) two.replace(strip + y * row + row / 2, row / 2, b, strip + y * row + row / 2, row / 2);
  spit(d + "two.tiff", two);

  const json::Value found = json::parse(run_shell(cli + " detect " + d + "two.tiff --chart cc24"));
  const auto& candidates = found.at("candidates").as_array();
  REQUIRE(candidates.size() == 2);
  Recipe r;
  r.reference.chart = "file";
  r.characterisation.model = "Finlayson2015-2";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  r.duplicates = kDuplicatesEach;
  RecipeImage e;
  e.name = "two.tiff";
  e.reference.chart = "file";
  e.sampling.layout.chart = "cc24";
  e.sampling.area = 0.5;
  std::string rgb;
  const auto g17 = [](double v) {
    std::ostringstream o;
    o << std::setprecision(17) << v;
    return o.str();
  };
  for (size_t k = 0; k < 2; ++k) {
    std::string list;
    size_t i = 0;
    for (const auto& corner : candidates[k].at("corners").as_array())
      for (double v : corner.as_numbers()) {
        e.sampling.corners[i++] = v;
        list += (list.empty() ? "" : ",") + g17(v);
      }
    r.images.push_back(e);
    const std::string csv = d + "s" + std::to_string(k) + ".csv";
    run_shell(cli + " sample " + d + "two.tiff --chart cc24 --area 0.5 --corners " + list + " > " + csv);
    rgb += " --rgb " + csv + " --xyz " + d + "ref.csv";
  }
  CHECK(r.images[0].sampling.corners[0] < 450);
  CHECK(r.images[1].sampling.corners[0] > 450);
  spit(d + "twice.json", recipe_to_json(r));
  Recipe mixed = r;  // a built-in reference for the first chart, the file for the second: one --xyz
  mixed.images[0].reference.chart = "cc24";
  mixed.images[0].reference.illuminant = "D65";
  spit(d + "mixed.json", recipe_to_json(mixed));
  r.images.resize(1);
  r.images[0].sampling.corners = {};
  r.images[0].candidate = "all";
  spit(d + "all.json", recipe_to_json(r));
  run_shell(cli + " reference --chart cc24 --illuminant D65 > " + d + "ref.csv");

  run_shell(cli + " fit" + rgb + " --model Finlayson2015-2 --objective ls --out " + d + "tables.json 2>&1");
  const std::string all = run_shell(cli + " fit --recipe " + d + "all.json --raw " + d + "two.tiff --xyz " + d + "ref.csv --out " +
                                    d + "all_p.json 2>&1");
  run_shell(cli + " fit --recipe " + d + "twice.json --raw " + d + "two.tiff --raw " + d + "two.tiff --xyz " + d + "ref.csv --xyz " +
            d + "ref.csv --out " + d + "twice_p.json 2>&1");
  const std::string tables = json_array(slurp(d + "tables.json"), "coefficients");
  CHECK(json_array(slurp(d + "all_p.json"), "coefficients") == tables);
  CHECK(json_array(slurp(d + "twice_p.json"), "coefficients") == tables);
  CHECK(slurp(d + "all_p.json").find("\"patches\": 48") != std::string::npos);
  CHECK(all.find("tristim: chart 1 (two.tiff #1): 24 patches") != std::string::npos);
  CHECK(all.find("tristim: chart 2 (two.tiff #2): 24 patches") != std::string::npos);
  // One --xyz per image whose reference is a file, the others their built-in chart.
  const std::string mix = d + "mixed.json --raw " + d + "two.tiff --raw " + d + "two.tiff";
  run_shell(cli + " fit --recipe " + mix + " --xyz " + d + "ref.csv --out " + d + "mixed_p.json 2>&1");
  CHECK(slurp(d + "mixed_p.json").find("\"patches\": 48") != std::string::npos);
  const std::string three = run_shell(cli + " fit --recipe " + mix + " --xyz " + d + "ref.csv --xyz " + d + "ref.csv --xyz " + d +
                          "ref.csv 2>&1; echo rc=$?", false);
  CHECK(three.find("INVALID_ARGUMENT: --xyz: give none (built-in references), one per --raw, or one per image whose "
                   "reference is a file (1), not 3") != std::string::npos);
  CHECK(three.find("rc=1") != std::string::npos);
  const std::string one = run_shell(cli + " fit --recipe " + d + "twice.json --raw " + d + "two.tiff --raw " + d + "two.tiff --xyz " + d +
                        "ref.csv 2>&1; echo rc=$?", false);
  CHECK(one.find("INVALID_ARGUMENT: --xyz:") != std::string::npos);
}
#endif

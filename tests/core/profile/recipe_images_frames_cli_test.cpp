// `tristim fit --recipe r.json --raw a.dng --dark a_d1.dng --dark a_d2.dng --raw b.dng --flat b_flat.dng`
// (issue 48; Abed 2013 App. C steps 1-2 per image): each --dark/--flat belongs to the --raw before
// it. Charts, dark frames and a flat rendered by `tristim lab render` (the flat: one white
// reflectance (three equal cells) filling the frame under a 1 - 0.3 r² fall-off, the charts under the same fall-off);
// the CLI's coefficients equal those of the same images and frames calibrated and fitted in
// process (sample_recipe_image with RecipeImageFrames, training_union, characterise), to the bit,
// and differ from the fit without the frames; misplaced frames are coded errors naming them
// (native only: it drives the CLI).
#ifndef __EMSCRIPTEN__
#include <string>

#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/profile/recipe.hpp"

using namespace tristim;
using namespace tristim::test;

namespace {

// A recipe of two images, each a built-in chart under D65 found by detection (corners all 0).
Recipe two_image_recipe() {
  Recipe r;
  r.reference.illuminant = "D65";
  r.characterisation.model = "Finlayson2015-2";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  for (const char* chart : {"cc24", "sg140"}) {
    RecipeImage e;
    e.name = std::string(chart) + ".dng";
    e.reference.chart = chart;
    e.reference.illuminant = "D65";
    e.sampling.layout.chart = chart;
    e.sampling.area = 0.5;
    r.images.push_back(e);
  }
  return r;
}

RawImage decoded(const std::string& path) {
  const std::string bytes = slurp(path);
  return decode_any(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

Eigen::MatrixXd cli_coefficients(const std::string& path) { return profile_from_json(slurp(path)).model.coefficients; }

}  // namespace

TEST_CASE("fit --recipe with images: per-image --dark and --flat equal the in-process calibrated fit, to the bit",
          "[recipe][images][frames][cli]") {
  const ScratchDir scratch("images_frames");
  const std::string& d = scratch.d;
  const std::string cli = TRISTIM_CLI;
  const std::string render = cli + " lab render --camera Canon_EOS_5D_Mark_II --illuminant D65 --size 600x400";
  run_shell(render + " --chart cc24 --falloff 0.3 --noise 0.5,3 --seed 1 --out " + d + "a.dng");
  run_shell(render + " --chart cc24 --exposure 1e-6 --noise 0.5,3 --seed 2 --out " + d + "a_d1.dng");
  run_shell(render + " --chart cc24 --exposure 1e-6 --noise 0.5,3 --seed 3 --out " + d + "a_d2.dng");
  run_shell(render + " --chart sg140 --falloff 0.3 --out " + d + "b.dng");
  std::string white = "id", row = "";
  for (int w = 380; w <= 780; w += 10) {
    white += "," + std::to_string(w);
    row += ",0.9";
  }
  spit(d + "white.csv", white + "\nW1" + row + "\nW2" + row + "\nW3" + row + "\n");  // 3 x 1 cells
  run_shell(render + " --reflectances " + d + "white.csv --corners 0,0,600,0,600,400,0,400 --falloff 0.3 --out " + d +
            "b_flat.dng");
  const Recipe recipe = two_image_recipe();
  spit(d + "r.json", recipe_to_json(recipe));

  // In process: the same files, the same frames.
  Recipe r = recipe;
  std::vector<ChartPart> parts;
  const std::vector<std::vector<std::string>> darks{{"a_d1.dng", "a_d2.dng"}, {}};
  const std::vector<std::vector<std::string>> flats{{}, {"b_flat.dng"}};
  for (size_t k = 0; k < 2; ++k) {
    RecipeImageFrames frames;
    for (const auto& f : darks[k]) frames.darks.push_back(decoded(d + f));
    for (const auto& f : flats[k]) frames.flat.push_back(decoded(d + f));
    const std::string bytes = slurp(d + (k == 0 ? "a.dng" : "b.dng"));
    const auto samples = sample_recipe_image(r.images[k], k, reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                             bytes.size(), frames);
    REQUIRE(samples.size() == 1);
    const Recipe own = image_recipe(r, r.images[k]);
    parts.push_back({r.images[k].name, training_set(own, samples[0], recipe_reference(own))});
  }
  CHECK(r.images[0].capture.dark_frames == 2);
  CHECK(r.images[1].capture.flat_field);
  const Characterisation c = characterise(r, training_union(r, parts));
  const Eigen::MatrixXd planted = profile_from_json(profile_to_json(c.profile)).model.coefficients;

  const std::string fit = cli + " fit --recipe " + d + "r.json";
  run_shell(fit + " --raw " + d + "a.dng --dark " + d + "a_d1.dng --dark " + d + "a_d2.dng --raw " + d + "b.dng --flat " +
            d + "b_flat.dng --out " + d + "framed.json --recipe-out " + d + "framed_recipe.json 2>&1");
  const Eigen::MatrixXd framed = cli_coefficients(d + "framed.json");
  REQUIRE(framed.rows() == 3);
  INFO("CLI:\n" << framed << "\nin process:\n" << planted);
  CHECK(framed == planted);
  // The recipe written records what was applied to each image.
  const Recipe written = recipe_from_json(slurp(d + "framed_recipe.json"));
  CHECK(written.images[0].capture.dark_frames == 2);
  CHECK(!written.images[0].capture.flat_field);
  CHECK(written.images[1].capture.dark_frames == 0);
  CHECK(written.images[1].capture.flat_field);

  // Without the frames the fit differs (the frames are used, not ignored).
  run_shell(fit + " --raw " + d + "a.dng --raw " + d + "b.dng --out " + d + "plain.json 2>&1");
  CHECK(cli_coefficients(d + "plain.json") != framed);

  // Misplaced frames: coded one-line errors naming them.
  const auto refused = [&](const std::string& args) { return run_shell(fit + args + " 2>&1; echo rc=$?", false); };
  std::string e = refused(" --dark " + d + "a_d1.dng --raw " + d + "a.dng --raw " + d + "b.dng");
  CHECK(e.find("INVALID_ARGUMENT: --dark '" + d + "a_d1.dng' comes before any --raw") != std::string::npos);
  CHECK(e.find("rc=1") != std::string::npos);
  e = refused(" --raw " + d + "a.dng --raw " + d + "b.dng --flat " + d + "b_flat.dng --flat " + d + "b_flat.dng");
  CHECK(e.find("INVALID_ARGUMENT: images[1] ('sg140.dng'): one flat field per image, not 2") != std::string::npos);
  e = refused(" --raw " + d + "a.dng --dark " + d + "missing.dng --raw " + d + "b.dng");
  CHECK(e.find("images[0] ('cc24.dng'): --dark '" + d + "missing.dng'") != std::string::npos);
  CHECK(e.find("rc=1") != std::string::npos);

  // --help names the per-image frames.
  const std::string help = run_shell(cli + " fit --help");
  CHECK(help.find("--raw a.dng [--dark d.dng ...] [--flat f.dng] --raw b.dng") != std::string::npos);
  CHECK(help.find("--dark (repeatable, averaged) and --flat are the frames of the --raw before them") != std::string::npos);
}
#endif

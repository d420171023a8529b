// The dark-frame mode has one spelling, "per_pixel" | "per_channel", in the CLI (--dark-mode), the
// recipe and profile JSON (capture.dark_mode), the page and the wasm binding (setDark). The
// aliases "pixel" | "channel" are read and mapped; every writer writes the canonical id.
#include <string>

#ifndef __EMSCRIPTEN__
#include <filesystem>
#endif

#include "test_support.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/profile/recipe.hpp"

using namespace tristim;
using test::read_test_file;
using test::require_code;

namespace {
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}
}  // namespace

TEST_CASE("dark mode: one id per mode, the aliases map to it", "[recipe][calibration][dark-mode]") {
  CHECK(std::string(dark_mode_id(DarkMode::PerPixel)) == "per_pixel");
  CHECK(std::string(dark_mode_id(DarkMode::PerChannel)) == "per_channel");
  for (DarkMode m : {DarkMode::PerPixel, DarkMode::PerChannel}) CHECK(dark_mode_from_id(dark_mode_id(m)) == m);
  CHECK(dark_mode_from_id("pixel") == DarkMode::PerPixel);
  CHECK(dark_mode_from_id("channel") == DarkMode::PerChannel);
  for (const char* bad : {"", "Pixel", "per-pixel", "per_pixels", "frame"}) {
    INFO(bad);
    try {
      dark_mode_from_id(bad);
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.code() == ErrorCode::InvalidArgument);
      CHECK(std::string(e.what()).find("per_pixel or per_channel") != std::string::npos);
    }
  }
}

TEST_CASE("recipe: capture.dark_mode round trip, the alias read and written canonically", "[recipe][dark-mode]") {
  Recipe r;
  r.reference.chart = "passport";
  r.capture.dark_frames = 4;
  r.capture.dark_mode = "per_channel";
  const std::string canonical = recipe_to_json(r);
  CHECK(canonical.find("\"dark_mode\": \"per_channel\"") != std::string::npos);
  CHECK(recipe_to_json(recipe_from_json(canonical)) == canonical);

  // The aliases, in a file and in a value (the page's and the binding's path, complete_recipe).
  const Recipe from_alias = recipe_from_json(replaced(canonical, "\"per_channel\"", "\"channel\""));
  CHECK(from_alias.capture.dark_mode == "per_channel");
  CHECK(recipe_to_json(from_alias) == canonical);
  CHECK(recipe_from_json(replaced(canonical, "\"per_channel\"", "\"pixel\"")).capture.dark_mode == "per_pixel");
  Recipe value = r;
  value.capture.dark_mode = "channel";
  CHECK(complete_recipe(value).capture.dark_mode == "per_channel");
  CHECK(recipe_to_json(value) == canonical);

  require_code([&] { recipe_from_json(replaced(canonical, "\"per_channel\"", "\"per-channel\"")); }, ErrorCode::InvalidArgument);
}

TEST_CASE("profile: an embedded recipe with the alias loads and is written canonically", "[recipe][profile][dark-mode]") {
  Recipe r;
  r.reference.chart = "passport";
  r.reference.illuminant = "D50";
  r.characterisation.model = "matrix-3x3";
  r.evaluation.leave_one_out = false;
  const ReferenceChart ref = recipe_reference(r);
  PatchMatrix rgb(24, 3), xyz(24, 3);
  for (int i = 0; i < 24; ++i) {
    xyz.row(i) = ref.XYZ[static_cast<size_t>(i)].transpose();
    rgb.row(i) << 0.4 * xyz(i, 0), 0.5 * xyz(i, 1) + 0.01 * xyz(i, 0), 0.3 * xyz(i, 2);
  }
  const Characterisation c = characterise(r, training_set(r, ref.ids, rgb, xyz));
  const std::string text = profile_to_json(c.profile);
  REQUIRE(text.find("\"dark_mode\": \"per_pixel\"") != std::string::npos);
  const Profile back = profile_from_json(replaced(text, "\"dark_mode\": \"per_pixel\"", "\"dark_mode\": \"pixel\""));
  CHECK(back.recipe.capture.dark_mode == "per_pixel");
  CHECK(profile_to_json(back) == text);
}

TEST_CASE("recipes on disk keep loading and are written in the canonical spelling", "[recipe][dark-mode]") {
  std::vector<std::string> files = {"examples/recipes/passport-rootpoly2-psm.json"};
#ifndef __EMSCRIPTEN__
  for (const auto& e : std::filesystem::directory_iterator(std::string(TRISTIM_SOURCE_DIR) + "/tests/fuzz/corpus/recipe"))
    if (e.path().extension() == ".json") files.push_back("tests/fuzz/corpus/recipe/" + e.path().filename().string());
  CHECK(files.size() > 10);
#endif
  for (const auto& f : files) {
    INFO(f);
    const Recipe r = recipe_from_json(read_test_file(f));
    CHECK((r.capture.dark_mode == "per_pixel" || r.capture.dark_mode == "per_channel"));
    const std::string out = recipe_to_json(r);
    CHECK(recipe_to_json(recipe_from_json(out)) == out);
    CHECK(out.find("\"pixel\"") == std::string::npos);
    CHECK(out.find("\"channel\"") == std::string::npos);
  }
}

#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
#include <cstdio>

namespace {
/// The CLI's stdout and exit status (stderr joined to stdout when `merge`).
std::string run_cli(const std::string& args, int& rc, bool merge = false) {
  FILE* f = popen((std::string(TRISTIM_CLI) + " " + args + (merge ? " 2>&1" : " 2>/dev/null")).c_str(), "r");
  REQUIRE(f != nullptr);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  rc = pclose(f);
  return out;
}
}  // namespace

TEST_CASE("cli: sample --dark-mode takes the canonical ids and the aliases alike", "[cli][dark-mode]") {
  const std::string dng = test::test_file_path("examples/web/passport.dng");
  const std::string base = "sample " + dng + " --chart passport --corners 335,291,649,285,649,486,328,488 --dark " + dng;
  int rc = 0;
  const std::string per_channel = run_cli(base + " --dark-mode per_channel", rc);
  REQUIRE(rc == 0);
  CHECK(run_cli(base + " --dark-mode channel", rc) == per_channel);
  const std::string per_pixel = run_cli(base + " --dark-mode per_pixel", rc);
  REQUIRE(rc == 0);
  CHECK(run_cli(base + " --dark-mode pixel", rc) == per_pixel);
  CHECK(run_cli(base, rc) == per_pixel);  // the default
  CHECK(per_pixel != per_channel);
  const std::string err = run_cli(base + " --dark-mode per-pixel", rc, true);
  CHECK(rc != 0);
  CHECK(err.find("INVALID_ARGUMENT") != std::string::npos);
  CHECK(err.find("per_pixel or per_channel") != std::string::npos);
  CHECK(run_cli("sample --help", rc).find("--dark-mode per_pixel|per_channel") != std::string::npos);
}
#endif

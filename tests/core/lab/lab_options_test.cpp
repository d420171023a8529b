// The lab's option table (lab_option_table) against the functions it bounds: every row's default
// is its struct's, every value at a bound is accepted and every value beyond one (or a fraction for
// an integer row) is refused by the lab function with INVALID_ARGUMENT (table4.noise: the surface
// step's row, which the simulated Table IV enforces); the reference CSV the page
// hands to the Reference step reads back as the truth's XYZ, to the bit.
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "refused.hpp"
#include "test_support.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

// A small render (64 × 64, the least the renderer draws) with one member set.
void render_with(const std::function<void(LabRenderOptions&)>& set) {
  LabRenderOptions o;
  o.width = o.height = 64;
  set(o);
  render_lab_chart(o);
}

// Exercise 2 on one model and one chart (the bound is checked before any fit).
void overfit_with(double noise) {
  OverfitOptions o;
  o.models = {"matrix-3x3"};
  o.training = {"cc24"};
  o.noise = noise;
  lab_overfit_exercise(camera_ssf("Nikon_D850"), illuminant_spd("D65"), o);
}

// The metamer search over one Munsell hue page (5R: a few dozen chips).
void metamers_with(const std::function<void(MetamerOptions&)>& set) {
  MetamerOptions o;
  set(o);
  metamer_pairs_in(o, lab_munsell_selection("5R"));
}

// Each row's function, given a value of that row.
std::map<std::string, std::function<void(double)>> functions() {
  return {
      {"render.exposure", {[](double v) { render_with([v](auto& o) { o.exposure = v; }); }}},
      {"render.shot_gain", {[](double v) { render_with([v](auto& o) { o.shot_gain = v; }); }}},
      {"render.read_noise", {[](double v) { render_with([v](auto& o) { o.read_noise = v; }); }}},
      {"render.falloff", {[](double v) { render_with([v](auto& o) { o.falloff = v; }); }}},
      {"render.flare", {[](double v) { render_with([v](auto& o) { o.flare = v; }); }}},
      // A seed is an unsigned integer: below 0 and fractions cannot reach the renderer (the CLI
      // and the page go through lab_option first); above the table's max it refuses.
      {"render.seed", {[](double v) {
         if (v < 0 || v != std::floor(v)) lab_option("render.seed", v);
         render_with([v](auto& o) { o.seed = static_cast<std::uint64_t>(v); });
       }}},
      {"overfit.noise", {overfit_with}},
      {"table4.noise", {[](double v) { lab_table4_exercise("Nikon_D850", "D50", v); }}},
      {"metamers.max_match", {[](double v) { metamers_with([v](auto& o) { o.max_match = v; }); }}},
      // top is an int: a fraction is checked as given, as the CLI and the page do before the cast.
      {"metamers.top", {[](double v) {
         if (v != std::floor(v)) lab_option("metamers.top", v);
         metamers_with([v](auto& o) { o.top = static_cast<int>(v); });
       }}},
  };
}

}  // namespace

TEST_CASE("lab options: each row's default is its struct's, and its form fields are set", "[lab]") {
  const LabRenderOptions render;
  const OverfitOptions overfit;
  const MetamerOptions metamers;
  const std::map<std::string, double> defaults{
      {"render.exposure", render.exposure}, {"render.shot_gain", render.shot_gain},
      {"render.read_noise", render.read_noise}, {"render.falloff", render.falloff},
      {"render.flare", render.flare}, {"render.seed", static_cast<double>(render.seed)},
      {"overfit.noise", overfit.noise}, {"table4.noise", kTable4Noise},
      {"metamers.max_match", metamers.max_match}, {"metamers.top", static_cast<double>(metamers.top)}};
  const auto table = lab_option_table();
  REQUIRE(table.size() == defaults.size());
  for (const OptionSpec& o : table) {
    INFO(o.name);
    REQUIRE(defaults.count(o.name) == 1);
    CHECK(o.default_number == defaults.at(o.name));
    CHECK(o.min < o.max);
    CHECK(o.default_number >= o.min);
    CHECK(o.default_number <= o.max);
    CHECK((o.type == "number" || o.type == "integer"));
    CHECK((o.type == "integer" ? o.step == 1 : o.step >= 0));
    CHECK(!o.label.empty());
    CHECK(!o.description.empty());
    CHECK(lab_option(o.name, o.default_number) == o.default_number);
  }
  test::require_code([] { lab_option("render.no_such", 1); }, ErrorCode::Internal);
}

TEST_CASE("lab options: every bound is the lab function's — accepted at it, refused beyond it", "[lab]") {
  const auto runs = functions();
  for (const OptionSpec& o : lab_option_table()) {
    INFO(o.name << " in [" << o.min << ", " << o.max << "]");
    REQUIRE(runs.count(o.name) == 1);  // a new row needs its function here
    const auto& run = runs.at(o.name);
    const double below = o.min - std::max(1.0, std::abs(o.min)) * 1e-6, above = o.max + std::max(1.0, std::abs(o.max)) * 1e-6;
    test::require_code([&] { run(o.type == "integer" ? std::floor(below) : below); }, ErrorCode::InvalidArgument);
    test::require_code([&] { run(o.type == "integer" ? std::ceil(above) : above); }, ErrorCode::InvalidArgument);
    test::require_code([&] { run(std::nan("")); }, ErrorCode::InvalidArgument);
    if (o.type == "integer") test::require_code([&] { run(o.min + 0.5); }, ErrorCode::InvalidArgument);
    CHECK_NOTHROW(run(o.min));
    CHECK_NOTHROW(run(o.max));
  }
}

TEST_CASE("lab render: the reference CSV reads back as the truth's XYZ, by cell for a grid", "[lab]") {
  for (const std::string chart : {"cc24", "munsell:5R4/14,10YR6/10,5PB5/10,5G5/8"}) {
    INFO(chart);
    LabRenderOptions o;
    o.width = o.height = 128;
    o.chart = chart;
    const LabRender r = render_lab_chart(o);
    const std::string csv = lab_reference_csv(r);
    CHECK(csv.rfind("id,X,Y,Z\n", 0) == 0);
    const PatchTable t = read_patch_csv(csv, "reference.csv");
    REQUIRE(t.has_XYZ);
    REQUIRE(t.ids.size() == r.patches.size());
    for (size_t i = 0; i < r.patches.size(); ++i) {
      const LabPatchTruth& p = r.patches[i];
      CHECK(t.labels[i] == (p.cell.empty() ? p.id : p.cell));
      for (int c = 0; c < 3; ++c) CHECK(t.XYZ[i][c] == p.XYZ[static_cast<size_t>(c)]);
    }
  }
}

TEST_CASE("lab file kinds: lab_render_files writes exactly these ids, each a file of its type", "[lab][catalog]") {
  std::string ids;
  for (const LabFileKind& k : lab_file_kinds()) {
    ids += k.id + " ";
    INFO(k.id);
    CHECK(!k.label.empty());
    LabRenderOptions o;
    o.width = o.height = 64;
    if (k.through_oecf) o.oecf = "sRGB";
    const std::vector<std::uint8_t> bytes = lab_render_files(o, k.id).dng;
    // A kind that is not encoded through the OECF refuses one (a DNG holds linear sensor data).
    LabRenderOptions encoded = o;
    encoded.oecf = "sRGB";
    if (!k.through_oecf) test::require_code([&] { lab_render_files(encoded, k.id); }, ErrorCode::InvalidArgument);
    REQUIRE(bytes.size() > 4);
    // The magic of the file its media type names: TIFF (a DNG is one) "II*\0", JPEG FF D8.
    if (k.media_type == "image/jpeg") CHECK((bytes[0] == 0xFF && bytes[1] == 0xD8));
    else CHECK((bytes[0] == 'I' && bytes[1] == 'I' && bytes[2] == 42 && bytes[3] == 0));
    CHECK((k.media_type == "image/jpeg") == (k.extension == "jpg"));
  }
  CHECK(ids == "dng tiff jpeg ");
  CHECK(lab_file_kinds().back().label.find(std::to_string(LabRenderOptions{}.jpeg_quality)) != std::string::npos);
  LabRenderOptions o;
  o.width = o.height = 64;
  test::require_code([&] { lab_render_files(o, "png"); }, ErrorCode::InvalidArgument);
}

TEST_CASE("metamer match table: the search takes exactly its viewers", "[lab][catalog]") {
  std::string ids;
  for (const MethodInfo& m : metamer_match_table()) {
    ids += m.id + " ";
    INFO(m.id);
    CHECK(!m.label.empty());
    CHECK(!m.reference.empty());
    CHECK_NOTHROW(metamers_with([&m](auto& o) {
      o.match = m.id;
      o.camera = "Nikon_D850";
    }));
  }
  CHECK(ids == "observer camera ");
  CHECK(MetamerOptions{}.match == metamer_match_table().front().id);
  test::require_code([] { metamers_with([](auto& o) { o.match = "eye"; }); }, ErrorCode::UnknownId);
}

TEST_CASE("shen training table: exercise 3 trains on exactly its charts", "[lab][catalog]") {
  const SpectralData ssf = camera_ssf("Nikon_D850");
  ShenOptions o;  // one J, one σ, one seed: the chart is what is checked
  o.J = {3};
  o.sigmas = {0};
  o.J_table = 3;
  o.seeds = 1;
  CHECK(ids_of(shen_training_table()) == "cc24, sg140");
  for (const MethodInfo& m : shen_training_table()) {
    INFO(m.id);
    CHECK(m.reference.find("Shen") != std::string::npos);
    o.chart = m.id;
    CHECK(lab_shen_exercise(ssf, o).chart == m.id);
  }
  CHECK(ShenOptions{}.chart == shen_training_table().front().id);
  o.chart = "passport";
  test::require_code([&] { lab_shen_exercise(ssf, o); }, ErrorCode::UnknownId);
}

// Several chart images in one recipe (issue 48): the `images` list round-trips exactly and leaves a
// recipe without it as it was; a fit on two charts through the recipe is, to the bit, the fit of
// their concatenated patch tables; a planted model is recovered from two charts with per-chart
// leave-one-out and held-out figures; duplicate colours weigh once; bad entries are refused with a
// code naming the image; two charts in one image are both sampled.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "chart_scene.hpp"
#include "test_support.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/profile/characterise.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {

// The message of the Error `f` throws, after checking its code.
std::string error_message(const std::function<void()>& f, ErrorCode code) {
  try {
    f();
  } catch (const Error& e) {
    CHECK(std::string(e.code_name()) == error_code_name(code));
    return e.what();
  }
  FAIL("no error thrown");
  return "";
}

struct Rendered {
  std::vector<std::uint8_t> bytes;
  LabRender render;
};

Rendered render(const std::string& chart, std::uint64_t seed) {
  LabRenderOptions o;
  o.chart = chart;
  o.width = 600, o.height = 400;
  o.shot_gain = 0.5, o.read_noise = 2, o.seed = seed;
  Rendered r;
  r.render = render_lab_chart(o);
  r.bytes = lab_render_dng(r.render);
  return r;
}

RecipeImage image_entry(const std::string& name, const std::string& chart, const std::array<double, 8>& corners) {
  RecipeImage e;
  e.name = name;
  e.reference.chart = chart;
  e.reference.illuminant = "D65";
  e.sampling.layout.chart = chart;
  e.sampling.corners = corners;
  e.sampling.area = 0.5;
  return e;
}

Recipe two_chart_recipe(const Rendered& a, const Rendered& b) {
  Recipe r;
  r.characterisation.model = "Finlayson2015-2";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  r.images = {image_entry("a.dng", "cc24", a.render.corners), image_entry("b.dng", "sg140", b.render.corners)};
  return r;
}

// What a user's concatenated tables hold: each image sampled on its own (sample_chart at the
// entry's corners), paired with its chart's reference by id, rows "k:id" one chart after the other.
void concatenated(const Recipe& r, const std::vector<const Rendered*>& shots, std::vector<std::string>& ids,
                  PatchMatrix& rgb, PatchMatrix& xyz) {
  std::vector<Vec3> R, X;
  for (size_t k = 0; k < shots.size(); ++k) {
    const RecipeImage& e = r.images[k];
    const RawImage image = decode_any(shots[k]->bytes);
    SampleOptions so;
    so.area = e.sampling.area;
    const ChartSample s = sample_chart(image, e.sampling.layout, e.sampling.corners, so);
    Recipe own = r;
    own.reference = e.reference;
    own.images.clear();
    const ReferenceChart ref = recipe_reference(own);
    for (const auto& p : s.patches) {
      size_t j = 0;
      while (ref.ids[j] != p.id) ++j;
      ids.push_back(std::to_string(k + 1) + ":" + p.id);
      R.emplace_back(p.mean[0], p.mean[1], p.mean[2]);
      X.push_back(ref.XYZ[j]);
    }
  }
  rgb.resize(static_cast<Eigen::Index>(R.size()), 3);
  xyz.resize(static_cast<Eigen::Index>(R.size()), 3);
  for (size_t i = 0; i < R.size(); ++i) {
    rgb.row(static_cast<Eigen::Index>(i)) = R[i].transpose();
    xyz.row(static_cast<Eigen::Index>(i)) = X[i].transpose();
  }
}

TrainingSet through_recipe(Recipe& r, const std::vector<const Rendered*>& shots) {
  std::vector<ChartPart> parts;
  for (size_t k = 0; k < shots.size(); ++k) {
    RecipeImage& e = r.images[k];
    const auto samples = sample_recipe_image(e, k, shots[k]->bytes.data(), shots[k]->bytes.size());
    const Recipe own = image_recipe(r, e);
    for (const auto& s : samples) parts.push_back({e.name, training_set(own, s, recipe_reference(own))});
  }
  return training_union(r, parts);
}

}  // namespace

TEST_CASE("recipe images: exact round trip, defaults from the recipe's stages, old recipes unchanged", "[recipe][images]") {
  Recipe plain;
  plain.reference.chart = "passport";
  plain.sampling.layout.chart = "passport";
  const std::string before = recipe_to_json(plain);
  CHECK(before.find("images") == std::string::npos);
  CHECK(before.find("duplicates") == std::string::npos);
  CHECK(recipe_to_json(recipe_from_json(before)) == before);

  Recipe r = plain;
  r.images = {image_entry("a.dng", "cc24", {1.5, 2, 101, 3, 99, 80.25, 0.1, 79}), image_entry("b.dng", "sg140", {})};
  r.images[1].candidate = "all";
  r.images[1].sha256 = std::string(64, 'a');
  r.images[0].capture.light_trap = {1, 1, 5, 1, 5, 5, 1, 5};
  r.images[0].capture.flare = {0.5, 0.25, 0.125};
  r.duplicates = kDuplicatesEach;
  const std::string text = recipe_to_json(r);
  const Recipe back = recipe_from_json(text);
  CHECK(recipe_to_json(back) == text);
  REQUIRE(back.images.size() == 2);
  CHECK(back.images[1].candidate == "all");
  CHECK(back.images[0].capture.flare[2] == 0.125);
  CHECK(back.duplicates == "each");
  r.images[1].candidate = "1";
  CHECK(recipe_to_json(r).find("\"candidate\": 1") != std::string::npos);
  CHECK(recipe_from_json(recipe_to_json(r)).images[1].candidate == "1");

  // An entry with a name only takes the recipe's reference, capture and sampling.
  const std::string short_form = before.substr(0, before.rfind('}')) + ", \"images\": [{\"name\": \"c.dng\"}]}";
  const Recipe s = recipe_from_json(short_form);
  REQUIRE(s.images.size() == 1);
  CHECK(s.images[0].reference.chart == "passport");
  CHECK(s.images[0].sampling.layout.chart == "passport");
  CHECK(s.duplicates == kDuplicatesOnce);
}

TEST_CASE("recipe images: bad entries are refused with a code naming the image", "[recipe][images]") {
  Recipe r;
  r.images = {image_entry("a.dng", "cc24", {}), image_entry("b.dng", "cc24", {})};
  const std::string good = recipe_to_json(r);
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.rfind(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
  };
  // The last "cc24" of the text is images[1]'s layout chart.
  CHECK(error_message([&] { recipe_from_json(edit("\"chart\": \"cc24\"", "\"chart\": \"cc99\"")); }, ErrorCode::UnknownId)
            .find("images[1] ('b.dng')") != std::string::npos);
  require_code([&] { recipe_from_json(edit("\"duplicates\": \"once\"", "\"duplicates\": \"twice\"")); },
               ErrorCode::InvalidArgument);
  require_code([&] { recipe_from_json(edit("\"name\": \"b.dng\"", "\"nom\": \"b.dng\"")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(edit("\"name\": \"b.dng\"", "\"name\": \"b.dng\", \"candidate\": -1")); },
               ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(edit("\"sha256\": \"\"", "\"sha256\": \"xyz\"")); },
               ErrorCode::RecipeInvalid);
  Recipe odd = r;
  odd.images[0].candidate = "first";
  CHECK(error_message([&] { recipe_to_json(odd); }, ErrorCode::RecipeInvalid).find("images[0] ('a.dng')") != std::string::npos);
  Recipe both = r;
  both.images[0].sampling.corners = {1, 1, 50, 1, 50, 30, 1, 30};
  both.images[0].candidate = "0";
  CHECK(error_message([&] { complete_recipe(both); }, ErrorCode::InvalidArgument).find("images[0] ('a.dng')") !=
        std::string::npos);

  // A file that does not decode: its decoder's code, the image named.
  const std::string junk = "this is no RAW file";
  RecipeImage e = r.images[1];
  CHECK(error_message([&] { sample_recipe_image(e, 1, reinterpret_cast<const std::uint8_t*>(junk.data()), junk.size()); },
                      ErrorCode::RawUnsupported)
            .find("images[1] ('b.dng')") != std::string::npos);
}

TEST_CASE("recipe images: a two-chart fit is the fit of the concatenated patch tables, to the bit", "[recipe][images]") {
  const Rendered a = render("cc24", 3), b = render("sg140", 4);
  for (const char* model : {"Finlayson2015-2", "matrix-3x3"}) {
    for (const char* objective : {"ls", "de2000"}) {
      INFO(model << " " << objective);
      Recipe r = two_chart_recipe(a, b);
      r.characterisation.model = model;
      r.characterisation.objective = MethodChoice{objective, {}, {}};
      r.evaluation.leave_one_out = std::string(objective) == "ls";
      const TrainingSet u = through_recipe(r, {&a, &b});
      REQUIRE(u.ids.size() == 164);
      CHECK(u.ids.front() == "1:A1");
      CHECK(u.ids.back().rfind("2:", 0) == 0);
      CHECK(r.images[0].sha256.size() == 64);
      const Characterisation two = characterise(r, u);

      std::vector<std::string> ids;
      PatchMatrix rgb, xyz;
      concatenated(r, {&a, &b}, ids, rgb, xyz);
      Recipe plain = r;
      plain.images.clear();
      const Characterisation one = characterise(plain, training_set(plain, ids, rgb, xyz));
      CHECK(ids == u.ids);
      CHECK(rgb == u.camera_RGB);
      CHECK(xyz == u.reference_XYZ);
      const Eigen::MatrixXd& c2 = two.evaluation.fit.model.coefficients;
      const Eigen::MatrixXd& c1 = one.evaluation.fit.model.coefficients;
      REQUIRE(c2.size() == c1.size());
      CHECK(std::memcmp(c2.data(), c1.data(), sizeof(double) * static_cast<size_t>(c1.size())) == 0);
      CHECK(two.evaluation.training.dE00.mean == one.evaluation.training.dE00.mean);
      // The profile records both images (names and SHA-256) through its recipe.
      REQUIRE(two.profile.recipe.images.size() == 2);
      CHECK(two.profile.recipe.images[1].name == "b.dng");
      CHECK(two.profile.recipe.images[1].sha256 == r.images[1].sha256);

      const std::vector<ChartFigures> f = chart_figures(two, u);
      REQUIRE(f.size() == 2);
      CHECK(f[0].patches == 24);
      CHECK(f[1].patches == 140);
      CHECK(f[0].has_loo == r.evaluation.leave_one_out);
      CHECK(f[0].has_held_out);
      CHECK(f[1].has_held_out);
      CHECK(f[0].training_dE00.mean > 0);
    }
  }
}

TEST_CASE("recipe images: a planted 3x3 is recovered from two charts, with figures per chart", "[recipe][images]") {
  Eigen::Matrix3d M;
  M << 0.61, 0.22, 0.12, 0.27, 0.69, 0.04, 0.01, 0.09, 0.83;  // camera RGB -> XYZ
  Recipe r;
  r.characterisation.model = "matrix-3x3";
  r.images = {image_entry("a", "cc24", {}), image_entry("b", "sg140", {})};
  r.images[0].candidate = "0";
  r.images[1].candidate = "0";
  std::vector<ChartPart> parts;
  for (const auto& e : r.images) {
    const Recipe own = image_recipe(r, e);
    const ReferenceChart ref = recipe_reference(own);
    PatchMatrix xyz(static_cast<Eigen::Index>(ref.ids.size()), 3);
    for (size_t i = 0; i < ref.ids.size(); ++i) xyz.row(static_cast<Eigen::Index>(i)) = ref.XYZ[i].transpose();
    const PatchMatrix rgb = xyz * M.inverse().transpose();
    parts.push_back({e.name, training_set(own, ref.ids, rgb, xyz)});
  }
  const TrainingSet u = training_union(r, parts);
  const Characterisation c = characterise(r, u);
  CHECK((c.evaluation.fit.model.coefficients - M).cwiseAbs().maxCoeff() < 1e-10);
  const std::vector<ChartFigures> f = chart_figures(c, u);
  REQUIRE(f.size() == 2);
  for (const auto& x : f) {
    INFO(x.name);
    CHECK(x.has_loo);
    CHECK(x.loo_dE00.max < 1e-6);
    REQUIRE(x.has_held_out);  // fitted on the other chart alone: the same planted matrix
    CHECK(x.held_out_dE00.max < 1e-6);
  }
  const json::Value j = fields::write(f);  // ChartFigures' field list
  CHECK(j.size() == 2);
  CHECK(j.dump().find("\"held_out\":{\"dE00_mean\":") != std::string::npos);
}

TEST_CASE("recipe images: two shots of one chart weigh once, or each with duplicates \"each\"", "[recipe][images]") {
  const Rendered a = render("cc24", 5), b = render("cc24", 6);  // the same chart, other noise
  Recipe r;
  r.characterisation.model = "matrix-3x3";
  r.images = {image_entry("a.dng", "cc24", a.render.corners), image_entry("b.dng", "cc24", b.render.corners)};
  const TrainingSet once = through_recipe(r, {&a, &b});
  REQUIRE(once.ids.size() == 24);
  CHECK(once.ids[0] == "1+2:A1");
  CHECK(once.chart_rows[0].size() == 24);
  CHECK(once.chart_rows[1].size() == 24);
  r.duplicates = kDuplicatesEach;
  const TrainingSet each = through_recipe(r, {&a, &b});
  REQUIRE(each.ids.size() == 48);
  CHECK(each.ids[24] == "2:A1");
  for (Eigen::Index i = 0; i < 24; ++i)
    CHECK((once.camera_RGB.row(i) - (each.camera_RGB.row(i) + each.camera_RGB.row(i + 24)) / 2).norm() < 1e-9);
  // A white patch named without its chart is the first row of that patch.
  r.duplicates = kDuplicatesOnce;
  r.characterisation.white_patch = "D1";
  int w = -1;
  recipe_fit_options(r, once.ids, once.camera_RGB, once.reference_XYZ, w);
  CHECK(once.ids[static_cast<size_t>(w)] == "1+2:D1");
  r.characterisation.white_patch = "2:D1";
  recipe_fit_options(r, once.ids, once.camera_RGB, once.reference_XYZ, w);
  CHECK(once.ids[static_cast<size_t>(w)] == "1+2:D1");
}

TEST_CASE("recipe images: two charts in one image, both detected and sampled (candidate \"all\")", "[recipe][images]") {
  SceneSpec big, small;
  big.chart = "cc24", big.area_fraction = 0.12, big.cx = 0.3, big.seed = 11, big.glare_patches = 0;
  small.chart = "cc24", small.area_fraction = 0.12, small.cx = 0.75, small.seed = 12, small.glare_patches = 0;
  const TwoChartScene scene = render_two_chart_scene(big, small);
  REQUIRE(scene.ok);
  // The scene as a 16-bit linear TIFF (what a user might export), as bytes.
  std::vector<std::uint16_t> px(scene.image.rgb.size());
  for (size_t i = 0; i < px.size(); ++i)
    px[i] = static_cast<std::uint16_t>(std::clamp(std::lround(scene.image.rgb[i]), 0L, 65535L));
  const std::vector<std::uint8_t> tiff = write_tiff_rgb16(px, scene.image.width, scene.image.height);
  RecipeImage e = image_entry("two.tif", "cc24", {});
  e.candidate = "all";
  const std::vector<ChartSample> all = sample_recipe_image(e, 0, tiff.data(), tiff.size());
  REQUIRE(all.size() == 2);
  CHECK(all[0].patches.size() == 24);
  CHECK(all[0].homography != all[1].homography);
  e.candidate = "5";
  CHECK(error_message([&] { sample_recipe_image(e, 0, tiff.data(), tiff.size()); }, ErrorCode::InvalidArgument)
            .find("images[0] ('two.tif'): candidate 5") != std::string::npos);
}

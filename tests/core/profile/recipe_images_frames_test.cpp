// Each image of a recipe with several (issue 48) calibrated by its own dark frames and flat field
// (Abed 2013 App. C steps 1-2, as `sample --dark --flat` for one image). Planted: two rendered
// charts, each photographed through its own light fall-off (a known stepped gradient g, across x
// for one, down y for the other) on its own per-pixel dark offset D; their flats are F·g + D and
// their dark frames D ± 1. With the frames the training set is the clean charts' samples scaled by
// the flat's mean F·mean(g) / F (App. C step 2 keeps DN: gain = mean / flat), and the fit is the fit
// of those corrected tables; without them it is not. A frame of another size is refused naming
// the image.
#include <cmath>
#include <functional>

#include "test_support.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/profile/characterise.hpp"

using namespace tristim;

namespace {

constexpr int kW = 400, kH = 300;  // measurement pixels; the sensor has 2·kW × 2·kH
constexpr double kF = 4000;        // the flat's level above the dark, DN

// The fall-off of image k at sensor pixel (sx, sy): 1, 1.125, … 1.875 in 8 steps across x (k = 0)
// or down y (k = 1), the same in each 2×2 CFA block, so that 8·n·g is a whole number of DN.
double gain(int k, int sx, int sy) {
  const int step = k == 0 ? 8 * (sx / 2) / kW : 8 * (sy / 2) / kH;
  return 1 + step / 8.0;
}
// The dark offset of image k at sensor pixel (sx, sy): a fixed pattern, 20..36 DN.
int offset(int k, int sx, int sy) { return 20 + (3 * sx + 5 * sy + 7 * k) % 17; }

struct Shot {
  LabRender clean;                      // the chart as it would be without fall-off or dark
  std::vector<std::uint8_t> bytes;      // what the camera recorded: black + D + clean·g
  RecipeImageFrames frames;             // its dark frames (D + 1, D − 1) and flat (F·g + D)
  std::array<double, 3> flat_mean{};    // the flat's channel mean above the dark (F · mean g)
};

RawImage decoded(const LabRender& r) { return decode_any(lab_render_dng(r)); }

Shot shoot(int k, const std::string& chart) {
  LabRenderOptions o;
  o.chart = chart;
  o.width = kW, o.height = kH;
  o.exposure = 0.3;
  o.shot_gain = 0.5, o.read_noise = 2, o.seed = 10 + static_cast<std::uint64_t>(k);
  Shot s;
  s.clean = render_lab_chart(o);
  const int black = o.black;
  LabRender seen = s.clean, flat = s.clean, dark_hi = s.clean, dark_lo = s.clean;
  double sum_g = 0;
  for (int sy = 0; sy < 2 * kH; ++sy)
    for (int sx = 0; sx < 2 * kW; ++sx) {
      const size_t i = static_cast<size_t>(sy) * 2 * kW + static_cast<size_t>(sx);
      // whole multiples of 8 DN above black, so that clean·g is exact
      const int signal = 8 * ((static_cast<int>(s.clean.sensor[i]) - black) / 8);
      s.clean.sensor[i] = static_cast<std::uint16_t>(black + signal);
      const double g = gain(k, sx, sy);
      const int d = offset(k, sx, sy);
      seen.sensor[i] = static_cast<std::uint16_t>(black + d + static_cast<int>(signal * g));
      flat.sensor[i] = static_cast<std::uint16_t>(black + d + static_cast<int>(kF * g));
      dark_hi.sensor[i] = static_cast<std::uint16_t>(black + d + 1);
      dark_lo.sensor[i] = static_cast<std::uint16_t>(black + d - 1);
      sum_g += g;
    }
  s.bytes = lab_render_dng(seen);
  s.frames.darks.push_back(decoded(dark_hi));
  s.frames.darks.push_back(decoded(dark_lo));
  s.frames.flat.push_back(decoded(flat));
  const double mean_g = sum_g / (4.0 * kW * kH);
  s.flat_mean = {kF * mean_g, kF * mean_g, kF * mean_g};
  return s;
}

RecipeImage entry(const std::string& name, const std::string& chart, const LabRender& r) {
  RecipeImage e;
  e.name = name;
  e.reference.chart = chart;
  e.reference.illuminant = "D65";
  e.sampling.layout.chart = chart;
  e.sampling.corners = r.corners;
  return e;
}

// The union of both images' training sets through the recipe, each with `frames` (or none).
TrainingSet through_recipe(Recipe& r, const std::vector<const Shot*>& shots, bool frames) {
  std::vector<ChartPart> parts;
  for (size_t k = 0; k < shots.size(); ++k) {
    RecipeImage& e = r.images[k];
    const auto samples = sample_recipe_image(e, k, shots[k]->bytes.data(), shots[k]->bytes.size(),
                                             frames ? shots[k]->frames : RecipeImageFrames{});
    const Recipe own = image_recipe(r, e);
    parts.push_back({e.name, training_set(own, samples.at(0), recipe_reference(own))});
  }
  return training_union(r, parts);
}

// The corrected tables a user would make by hand: each clean chart sampled at its corners, its
// camera RGB scaled by the flat's mean over F, paired with its reference; rows "k:id".
TrainingSet corrected_tables(const Recipe& r, const std::vector<const Shot*>& shots) {
  std::vector<std::string> ids;
  std::vector<Vec3> rgb, xyz;
  for (size_t k = 0; k < shots.size(); ++k) {
    const RecipeImage& e = r.images[k];
    const ChartSample s = sample_chart(decoded(shots[k]->clean), e.sampling.layout, e.sampling.corners);
    const ReferenceChart ref = recipe_reference(image_recipe(r, e));
    for (const auto& p : s.patches) {
      size_t j = 0;
      while (ref.ids[j] != p.id) ++j;
      ids.push_back(std::to_string(k + 1) + ":" + p.id);
      Vec3 v;
      for (int c = 0; c < 3; ++c) v[c] = p.mean[c] * shots[k]->flat_mean[static_cast<size_t>(c)] / kF;
      rgb.push_back(v);
      xyz.push_back(ref.XYZ[j]);
    }
  }
  PatchMatrix R(static_cast<Eigen::Index>(rgb.size()), 3), X(static_cast<Eigen::Index>(rgb.size()), 3);
  for (size_t i = 0; i < rgb.size(); ++i) {
    R.row(static_cast<Eigen::Index>(i)) = rgb[i].transpose();
    X.row(static_cast<Eigen::Index>(i)) = xyz[i].transpose();
  }
  Recipe plain = r;
  plain.images.clear();
  return training_set(plain, ids, R, X);
}

double worst_relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("recipe images: each image's own dark frames and flat field, planted fall-off and dark offset",
          "[recipe][images][frames]") {
  const Shot a = shoot(0, "cc24"), b = shoot(1, "cc24");
  Recipe r;
  r.characterisation.model = "matrix-3x3";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  r.evaluation.leave_one_out = false;
  r.duplicates = kDuplicatesEach;
  r.images = {entry("a.dng", "cc24", a.clean), entry("b.dng", "cc24", b.clean)};

  Recipe with = r;
  const TrainingSet u = through_recipe(with, {&a, &b}, true);
  const TrainingSet t = corrected_tables(r, {&a, &b});
  REQUIRE(u.ids == t.ids);
  CHECK(with.images[0].capture.dark_frames == 2);
  CHECK(with.images[1].capture.flat_field);
  CHECK(!with.images[1].capture.falloff);
  // Exact in DN before float32 gains: every patch within 1e-6 of the corrected table.
  const double rgb_error = worst_relative(u.camera_RGB, t.camera_RGB);
  INFO("worst patch RGB difference (relative to the largest): " << rgb_error);
  CHECK(rgb_error < 1e-6);
  CHECK(u.reference_XYZ == t.reference_XYZ);

  const Characterisation fitted = characterise(with, u);
  Recipe plain = r;
  plain.images.clear();
  const Characterisation by_hand = characterise(plain, t);
  const double coef_error = worst_relative(fitted.evaluation.fit.model.coefficients, by_hand.evaluation.fit.model.coefficients);
  INFO("worst coefficient difference (relative to the largest): " << coef_error);
  CHECK(coef_error < 1e-6);
  REQUIRE(fitted.profile.recipe.images.size() == 2);
  CHECK(fitted.profile.recipe.images[0].capture.dark_frames == 2);

  // Without the frames the fall-off and the offset stay in the patches: not the corrected tables.
  Recipe without = r;
  const TrainingSet raw = through_recipe(without, {&a, &b}, false);
  CHECK(worst_relative(raw.camera_RGB, t.camera_RGB) > 0.1);
  CHECK(without.images[0].capture.dark_frames == 0);
}

TEST_CASE("recipe images: a frame of another size is refused naming the image", "[recipe][images][frames]") {
  const Shot a = shoot(0, "cc24");
  LabRenderOptions o;
  o.width = kW / 2, o.height = kH / 2;
  const RawImage small = decoded(render_lab_chart(o));
  Recipe r;
  r.images = {entry("a.dng", "cc24", a.clean), entry("b.dng", "cc24", a.clean)};
  const auto message = [&](const RecipeImageFrames& f) {
    try {
      sample_recipe_image(r.images[1], 1, a.bytes.data(), a.bytes.size(), f);
    } catch (const Error& e) {
      CHECK(e.code() == ErrorCode::FrameMismatch);
      return std::string(e.what());
    }
    FAIL("no error thrown");
    return std::string();
  };
  RecipeImageFrames dark;
  dark.darks.push_back(small);
  const std::string d = message(dark);
  CHECK(d.find("images[1] ('b.dng'): its dark frames") != std::string::npos);
  RecipeImageFrames flat;
  flat.flat.push_back(small);
  const std::string f = message(flat);
  CHECK(f.find("images[1] ('b.dng'): its flat field") != std::string::npos);
  RecipeImageFrames two = a.frames;
  two.flat.push_back(a.frames.flat[0]);
  CHECK_THROWS_AS(sample_recipe_image(r.images[0], 0, a.bytes.data(), a.bytes.size(), two), Error);
}

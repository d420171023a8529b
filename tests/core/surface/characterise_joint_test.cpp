// Phase II as an option of the normal fit path: a recipe whose surface stage has fit = "joint" is
// fitted by characterise() jointly with a 3×3 anchored to the chart's white patch.
#include <catch2/catch.hpp>

#include "test_support.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;

namespace {

// A colorimetric camera (RGB = A⁻¹·XYZ) seeing the SG through a scaler-offset correction that
// leaves the white patch where the instrument measured it (the anchoring assumption: the white
// reads the same in both geometries): ρ = (1 − μ)·Y_white.
struct Scene {
  Recipe recipe;
  TrainingSet training;
  double mu = 0.96, rho = 0;  // blacks read lighter, as in a diffuse booth
};
Scene planted() {
  Scene s;
  s.recipe.reference.chart = "sg140-2005";
  s.recipe.characterisation.white_patch = "J1";  // the SG's lightest white (Y 91.4 under D50)
  const ReferenceChart measured = recipe_reference(s.recipe);
  size_t w = 0;
  while (normalise_patch_id(measured.ids[w]) != "J1") ++w;
  s.rho = (1 - s.mu) * measured.XYZ[w][1] / measured.white[1];
  Recipe truth = s.recipe;
  truth.surface = surface_choice("scaler-offset", {s.mu, s.rho});
  const ReferenceChart seen = recipe_reference(truth);
  Mat3 A_inv;
  A_inv << 0.9, 0.2, -0.1, -0.3, 1.2, 0.1, 0.05, -0.1, 1.1;
  PatchMatrix rgb(static_cast<Eigen::Index>(seen.ids.size()), 3), xyz(rgb.rows(), 3);
  for (size_t i = 0; i < seen.ids.size(); ++i) {
    rgb.row(static_cast<Eigen::Index>(i)) = (A_inv * seen.XYZ[i]).transpose();
    xyz.row(static_cast<Eigen::Index>(i)) = measured.XYZ[i].transpose();
  }
  s.training = training_set(s.recipe, measured.ids, rgb, xyz);
  return s;
}

}  // namespace

TEST_CASE("characterise: surface fit 'joint' recovers a planted scaler-offset (Phase II in the fit path)", "[surface][joint]") {
  Scene s = planted();
  s.recipe.surface = {"scaler-offset", {}, {{"fit", "joint"}}};
  const Characterisation c = characterise(s.recipe, s.training);
  INFO("fitted " << surface_choice_text(c.surface) << ", planted mu " << s.mu << " rho " << s.rho);
  CHECK(c.surface.method == "scaler-offset");
  CHECK(c.surface.settings.at("fit") == "fixed");
  CHECK(c.surface.parameters.at("mu") == Approx(s.mu).margin(0.01));
  CHECK(c.surface.parameters.at("rho") == Approx(s.rho).margin(0.01));
  CHECK(c.profile.recipe.surface.settings.at("fit") == "joint");  // the profile records how it was made

  // Without the correction the 3×3 cannot reach the planted reference; with it, it nearly does.
  Scene plain = planted();
  const Characterisation none = characterise(plain.recipe, plain.training);
  INFO("mean ΔE00 without " << none.evaluation.training.dE00.mean << ", joint " << c.evaluation.training.dE00.mean);
  CHECK(c.evaluation.training.dE00.mean < 0.25 * none.evaluation.training.dE00.mean);
  // The training reference is the fitted correction's: the same as the recipe_reference of c.surface.
  Recipe fixed = s.recipe;
  fixed.surface = c.surface;
  const ReferenceChart again = recipe_reference(fixed);
  CHECK((c.reference_XYZ.row(0).transpose() - again.XYZ[0]).norm() < 1e-9);
}

TEST_CASE("characterise: a joint surface fit needs the white patch and a built-in chart", "[surface][joint]") {
  Scene s = planted();
  s.recipe.surface = {"offset", {}, {{"fit", "joint"}}};
  s.recipe.characterisation.white_patch = "";
  test::require_code([&] { characterise(s.recipe, s.training); }, ErrorCode::IllPosed);
  s.recipe.characterisation.white_patch = "J1";
  s.recipe.reference.chart = "file";
  test::require_code([&] { characterise(s.recipe, s.training); }, ErrorCode::InvalidArgument);
  s.recipe.reference.chart = "sg140-2005";
  s.recipe.surface.settings["fit"] = "later";
  test::require_code([&] { characterise(s.recipe, s.training); }, ErrorCode::InvalidArgument);
}

TEST_CASE("surface choice text leaves the default fit out and keeps 'joint'", "[surface]") {
  CHECK(surface_choice_text(surface_choice("offset", {0.01})) == "offset:rho=0.01");
  MethodChoice j = surface_choice("offset", {0.01});
  j.settings["fit"] = "joint";
  CHECK(surface_choice_text(j) == "offset:rho=0.01,fit=joint");
  CHECK(parse_choice(surface_choice_text(j)).settings.at("fit") == "joint");
}

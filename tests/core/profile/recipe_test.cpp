// Recipes: exact JSON round trip over every built-in combination, strict reading with codes,
// and the recipe's data path (characterise) giving the same numbers as the direct calls.
#include <random>

#include "test_support.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

Recipe passport_recipe() {
  Recipe r;
  r.reference.chart = "passport";
  r.reference.illuminant = "D50";
  r.sampling.layout.chart = "passport";
  r.sampling.corners = {335, 291, 649, 285, 649, 486, 328, 488};
  r.characterisation.model = "Finlayson2015-2";
  r.characterisation.objective = MethodChoice{"psm", {{"max_iterations", 300}}, {}};
  r.characterisation.white_patch = "D1";
  return r;
}

}  // namespace

TEST_CASE("recipe JSON round-trips exactly on every built-in combination", "[recipe]") {
  int checked = 0;
  for (const auto& chart : list_charts()) {
    for (const char* illuminant : {"A", "D50", "D65", "F11", "D4000"}) {
      for (const char* observer : {"1931", "1964"}) {
        for (const auto& model : model_table()) {
          for (const auto& objective : objective_table()) {
            for (const auto& lin : linearisation_table()) {
              for (const auto& surf : surface_table()) {
                Recipe r;
                r.reference.chart = chart.id;
                r.reference.illuminant = illuminant;
                r.reference.observer = observer;
                r.sampling.layout.chart = chart.id;
                r.sampling.corners = {1.25, 2.5, 101.125, 3, 99.0625, 80.5, 0.1, 79.9};
                r.sampling.exclude = {"a3"};
                r.characterisation.model = model.id;
                r.characterisation.objective.method = objective.info.id;
                r.characterisation.lab_white = Vec3(95.047, 100, 108.883);
                r.linearisation.method = lin.info.id;
                r.surface.method = surf.info.id;
                const std::string text = recipe_to_json(r);
                const Recipe back = recipe_from_json(text);
                INFO(chart.id << " " << illuminant << " " << observer << " " << model.id << " " << objective.info.id);
                REQUIRE(recipe_to_json(back) == text);
                CHECK(back.sampling.corners == r.sampling.corners);
                CHECK(back.sampling.exclude == std::vector<std::string>{"A3"});
                CHECK(back.characterisation.lab_white == r.characterisation.lab_white);
                CHECK(back.characterisation.objective.parameters ==
                      complete_choice(objective.info, r.characterisation.objective).parameters);
                ++checked;
              }
            }
          }
        }
      }
    }
  }
  CHECK(checked == static_cast<int>(list_charts().size() * 5 * 2 * model_table().size() * objective_table().size() *
                                    linearisation_table().size() * surface_table().size()));
}

TEST_CASE("recipe options survive the round trip bit for bit", "[recipe]") {
  Recipe r = passport_recipe();
  r.characterisation.objective = MethodChoice{"de2000", {{"rms", 1}, {"xtol_rel", 0.1 + 0.2}}, {{"algorithm", "lm"}}};
  r.capture.saturation = 15000.0 / 7.0;
  r.sampling.area = 1.0 / 3.0;
  const Recipe back = recipe_from_json(recipe_to_json(r));
  CHECK(back.characterisation.objective.parameters.at("xtol_rel") == 0.1 + 0.2);
  CHECK(back.characterisation.objective.settings.at("algorithm") == "lm");
  CHECK(back.capture.saturation == 15000.0 / 7.0);
  CHECK(back.sampling.area == 1.0 / 3.0);
  CHECK_FALSE(back.capture.has_light_trap());
  CHECK(recipe_to_json(r).find("light_trap") == std::string::npos);  // only recipes with a trap have it
  // A light trap (Abed 2013 App. C step 1): its corners and the flare measured there round-trip.
  r.capture.light_trap = {603.5, 443, 643, 443, 643, 481.25, 603.5, 481.25};
  r.capture.flare = {1.0 / 3.0, 2.5, 0.1};
  const Recipe trapped = recipe_from_json(recipe_to_json(r));
  CHECK(trapped.capture.light_trap == r.capture.light_trap);
  CHECK(trapped.capture.flare == r.capture.flare);
  CHECK(recipe_to_json(trapped) == recipe_to_json(r));
  FitOptions o;
  apply_objective_choice(back.characterisation.objective, o);
  CHECK(o.objective == Objective::DeltaE2000);
  CHECK(o.de2000.rms);
  CHECK(o.de2000.algorithm == "lm");
  // The engine's defaults come from the option structs: the page's CIEDE2000 default is "auto".
  CHECK(complete_choice(objective_method("de2000").info, MethodChoice{"de2000", {}, {}}).settings.at("algorithm") ==
        DeltaE2000Options().algorithm);
}

TEST_CASE("malformed recipes are refused with a code naming the field", "[recipe]") {
  const std::string good = recipe_to_json(passport_recipe());
  REQUIRE_NOTHROW(recipe_from_json(good));
  require_code([&] { recipe_from_json(replace(good, "\"version\": 1", "\"version\": 2")); }, ErrorCode::RecipeVersion);
  require_code([&] { recipe_from_json(replace(good, "\"version\": 1,", "")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "tristim-recipe", "tristim-profile")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(std::string("{\"format\": \"tristim-recipe\"")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(std::string("[1, 2]")); }, ErrorCode::RecipeInvalid);
  // Unknown fields at any level, wrong types, missing fields.
  require_code([&] { recipe_from_json(replace(good, "\"version\": 1,", "\"version\": 1, \"colour\": 1,")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"area\": 0.5", "\"area\": 0.5, \"extra\": []")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"area\": 0.5", "\"area\": \"half\"")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"leave_one_out\": true", "\"leave_one_out\": 1")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"falloff\": false,", "")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"corners\": [335", "\"corners\": [")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"noise_floor\": 0", "\"noise_floor\": 0, \"light_trap\": [1, 2, 3]")); }, ErrorCode::RecipeInvalid);
  require_code([&] { recipe_from_json(replace(good, "\"noise_floor\": 0", "\"noise_floor\": 0, \"light_trap\": [0, 0, 0, 0, 0, 0, 0, 0], \"flare\": [0, 0, 0]")); }, ErrorCode::RecipeInvalid);
  // Unknown ids and options, out-of-range values.
  require_code([&] { recipe_from_json(replace(good, "Finlayson2015-2", "Finlayson2015-9")); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replace(good, "\"method\": \"identity\"", "\"method\": \"magic\"")); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replace(good, "\"method\": \"none\"", "\"method\": \"gloss\"")); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replace(good, "\"expansion\": 2", "\"expansion\": 2, \"gamma\": 3")); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replace(good, "\"contraction\": 0.5", "\"contraction\": 7")); }, ErrorCode::InvalidArgument);
  require_code([&] { recipe_from_json(replace(good, "\"illuminant\": \"D50\"", "\"illuminant\": \"D2\"")); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replace(good, "\"chart\": \"passport\"", "\"chart\": \"cc99\"")); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replace(good, "\"area\": 0.5", "\"area\": 0")); }, ErrorCode::InvalidArgument);
}

TEST_CASE("characterise(recipe) gives the numbers of the direct calls, and the profile embeds the recipe",
          "[recipe]") {
  const Recipe r = passport_recipe();
  const ReferenceChart ref = recipe_reference(r);
  const ReferenceChart direct = reference_chart("passport", "D50");
  REQUIRE(ref.XYZ.size() == direct.XYZ.size());
  for (size_t i = 0; i < ref.XYZ.size(); ++i) CHECK(ref.XYZ[i] == direct.XYZ[i]);  // surface "none": bitwise

  // Camera RGB from a planted 3×3 plus a little structure (any RGB does: the check is identity of paths).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.98, 1.02);
  PatchMatrix rgb(24, 3), xyz(24, 3);
  for (int i = 0; i < 24; ++i) {
    xyz.row(i) = ref.XYZ[i].transpose();
    rgb.row(i) << 40 * xyz(i, 0) * u(rng), 38 * xyz(i, 1) * u(rng), 30 * xyz(i, 2) * u(rng);
  }
  const TrainingSet t = training_set(r, ref.ids, rgb, xyz);
  const Characterisation c = characterise(r, t);

  int white = -1;
  const FitOptions o = recipe_fit_options(r, ref.ids, rgb, xyz, white);
  REQUIRE(white == 18);  // D1
  const ModelEvaluation ev = evaluate_model("Finlayson2015-2", rgb, xyz, o, white, true);
  CHECK(c.evaluation.fit.model.coefficients == ev.fit.model.coefficients);
  CHECK(c.evaluation.loo.dE00.mean == ev.loo.dE00.mean);
  CHECK(c.profile.white_preserved);

  const Profile back = profile_from_json(profile_to_json(c.profile));
  REQUIRE(back.has_recipe);
  CHECK(recipe_to_json(back.recipe) == recipe_to_json(r));
  // A profile whose embedded recipe is tampered with is refused with the recipe's code.
  const std::string text = profile_to_json(c.profile);
  require_code([&] { profile_from_json(replace(text, "\"exclude_flagged\": false", "\"exclude_flagged\": 0")); },
               ErrorCode::RecipeInvalid);

  // Exclusions leave patches out and say which.
  Recipe ex = r;
  ex.sampling.exclude = {"a1", "B2"};
  const TrainingSet t2 = training_set(ex, ref.ids, rgb, xyz);
  CHECK(t2.ids.size() == 22);
  CHECK(t2.excluded == std::vector<std::string>{"A1 (excluded)", "B2 (excluded)"});
  Recipe wrong_white = r;
  wrong_white.characterisation.white_patch = "Z9";
  require_code([&] { characterise(wrong_white, t); }, ErrorCode::UnknownId);
}

TEST_CASE("characterise: the linearisation stage reads the recipe's capture full scale", "[recipe][linearisation]") {
  // Planted: camera RGB = a 3×3 of XYZ, sRGB-encoded to 8-bit codes (no rounding), the white at
  // 200 of 255. With capture.saturation = 255 the sRGB row decodes exactly (x = code / 255) and a
  // 3×3 fits to ~0; with 0 (x = code / the data's max) the curve is read at the wrong scale.
  Recipe r = passport_recipe();
  r.characterisation.model = "matrix-3x3";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  r.characterisation.white_patch = "";
  r.linearisation = MethodChoice{"sRGB", {}, {}};
  const ReferenceChart ref = recipe_reference(r);
  Mat3 M;
  M << 0.7, 0.3, 0.05, 0.2, 0.9, 0.1, 0.05, 0.1, 0.9;
  PatchMatrix rgb(24, 3), xyz(24, 3);
  for (int i = 0; i < 24; ++i) {
    xyz.row(i) = ref.XYZ[i].transpose();
    const Vec3 lin = M * ref.XYZ[i] / (ref.white[1] * 1.45);
    for (int c = 0; c < 3; ++c) rgb(i, c) = 255 * sRGB_encode(std::max(lin[c], 1e-4));
  }
  REQUIRE(rgb.maxCoeff() < 255);
  r.capture.saturation = 255;
  const Characterisation c = characterise(r, training_set(r, ref.ids, rgb, xyz));
  CHECK(c.linearisation.full_scale == 255);
  CHECK(c.evaluation.training.dE00.mean < 1e-3);
  r.capture.saturation = 0;
  const Characterisation wrong = characterise(r, training_set(r, ref.ids, rgb, xyz));
  CHECK(wrong.linearisation.full_scale == Approx(rgb.maxCoeff()));
  INFO("dE00 mean " << c.evaluation.training.dE00.mean << " at 255, " << wrong.evaluation.training.dE00.mean << " at the max");
  CHECK(wrong.evaluation.training.dE00.mean > 0.1);  // 0.22 measured
}

TEST_CASE("method choices: defaults, bounds and the CLI syntax", "[recipe]") {
  const MethodChoice c = parse_choice("psm:expansion=3,max_iterations=50");
  CHECK(c.method == "psm");
  CHECK(c.parameters.at("expansion") == 3);
  const MethodChoice done = complete_choice(objective_method("psm").info, c);
  CHECK(done.parameters.at("contraction") == PatternSearchOptions().contraction);
  require_code([] { complete_choice(objective_method("psm").info, parse_choice("psm:max_iterations=1.5")); },
               ErrorCode::InvalidArgument);
  require_code([] { complete_choice(objective_method("de2000").info, parse_choice("de2000:algorithm=magic")); },
               ErrorCode::InvalidArgument);
  require_code([] { complete_choice(objective_method("de2000").info, parse_choice("de2000:rms=2")); },
               ErrorCode::InvalidArgument);
  require_code([] { parse_choice("psm:expansion"); }, ErrorCode::InvalidArgument);
  require_code([] { parse_choice(":x=1"); }, ErrorCode::InvalidArgument);
}

TEST_CASE("a profile fitted with a linearisation stage takes stored values everywhere", "[recipe][profile]") {
  // Stored 8-bit-scale values of a planted 3×3 under a 1/2.2 encoding: v = 255 (M·XYZ / s)^(1/2.2).
  Recipe r = passport_recipe();
  r.characterisation.model = "matrix-3x3";
  r.characterisation.objective = MethodChoice{"ls", {}, {}};
  r.linearisation = MethodChoice{"gamma", {{"gamma", 2.2}}, {}};
  r.capture.saturation = 255;
  const ReferenceChart ref = recipe_reference(r);
  PatchMatrix stored(24, 3), xyz(24, 3);
  Mat3 M;
  M << 0.9, 0.2, -0.1, 0.1, 1.0, 0.05, 0.0, 0.1, 0.8;
  for (int i = 0; i < 24; ++i) {
    xyz.row(i) = ref.XYZ[i].transpose();
    const Vec3 lin = M * ref.XYZ[i] / 110.0;
    for (int c = 0; c < 3; ++c) stored(i, c) = 255.0 * std::pow(std::max(0.0, lin[c]), 1 / 2.2);
  }
  const Characterisation c = characterise(r, training_set(r, ref.ids, stored, xyz));
  REQUIRE(c.profile.has_linearisation);
  CHECK(c.profile.linearisation.choice.method == "gamma");
  CHECK(c.profile.rgb_max == 255);  // device 1.0 of the exports = the encoding's full scale
  CHECK(c.evaluation.training.dE00.max < 0.05);  // the planted 3×3 is found through the gamma
  // Read back: the linearisation survives, predictions on stored values are the fit's, bit for bit.
  const std::string text = profile_to_json(c.profile);
  const Profile back = profile_from_json(text);
  REQUIRE(back.has_linearisation);
  CHECK(profile_to_json(back) == text);
  const PatchMatrix est = profile_predict(back, stored);
  CHECK(est == c.evaluation.fit.fitted);
  CHECK(training_digest(ref.ids, stored, xyz) == back.training_digest);
  // apply_profile on a stored-value image: the same XYZ as the patches (float image, float tolerance).
  std::vector<float> img;
  for (int i = 0; i < 24; ++i)
    for (int k = 0; k < 3; ++k) img.push_back(static_cast<float>(stored(i, k)));
  const Image3f out = apply_profile(back, img.data(), 24, 1);
  double worst = 0;
  for (int i = 0; i < 24; ++i)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(out.pixels[3 * i + k] - est(i, k)) / 100.0);
  CHECK(worst < 1e-5);
  // ICC (LUT form, the linearisation in it) read back by lcms2, and the .cube: close to the model.
  const PatchMatrix icc = icc_device_to_XYZ(export_icc(back), stored / 255.0);
  double icc_worst = 0;
  for (int i = 0; i < 24; ++i) icc_worst = std::max(icc_worst, (icc.row(i) * 100.0 - est.row(i)).cwiseAbs().maxCoeff());
  INFO("worst ICC patch error (XYZ, Y = 100): " << icc_worst);
  CHECK(icc_worst < 0.5);
  CHECK(export_cube(back).find("gamma linearisation is inside the LUT") != std::string::npos);
  // Without a linearisation stage (identity) nothing changes: no "linearisation" member.
  Recipe plain = passport_recipe();
  const Characterisation p = characterise(plain, training_set(plain, ref.ids, stored, xyz));
  CHECK_FALSE(p.profile.has_linearisation);
  CHECK_FALSE(profile_from_json(profile_to_json(p.profile)).has_linearisation);  // (no top-level member)
}

TEST_CASE("catalog: an objective choice reads as the loss and optimiser it runs", "[recipe][catalog]") {
  CHECK(objective_choice_label(parse_choice("ls")) == objective_method("ls").info.label);
  CHECK(objective_choice_label(parse_choice("de2000")) == "CIEDE2000 mean (reweighted Levenberg-Marquardt)");
  CHECK(objective_choice_label(parse_choice("de2000:rms=1")) == "CIEDE2000 RMS (Levenberg-Marquardt)");
  CHECK(objective_choice_label(parse_choice("de2000:algorithm=bobyqa")) == "CIEDE2000 mean (NLopt bobyqa)");
  tristim::test::require_code([] { objective_choice_label(parse_choice("de2000:algorithm=nope")); }, ErrorCode::InvalidArgument);
}

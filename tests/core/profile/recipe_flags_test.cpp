// The recipe's sample-flag rule (sampling.exclude_flags, issue 43: the engine, not the page,
// decides which flags leave a patch out) and the record of a chart cut by the frame
// (sampling.missing, issue 48), on a planted chart sample: camera RGB made from a known 3×3, a
// few patches flagged, one outside the frame.
#include <Eigen/LU>

#include "test_support.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/profile/characterise.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {

const Mat3 kPlanted = (Mat3() << 0.02, 0.004, 0.001, 0.003, 0.025, 0.002, 0.0005, 0.003, 0.03).finished();

/// cc24 under D50 sampled through kPlanted (camera RGB = M · XYZ), D6 outside the frame, and
/// flags: A1 saturated, A2 dark, A3 nonuniform, A4 saturated and dark.
ChartSample planted_sample(const ReferenceChart& ref) {
  ChartSample s;
  for (size_t k = 0; k < ref.ids.size(); ++k) {
    if (ref.ids[k] == "D6") {
      s.missing.push_back("d6");  // as a user's spelling: recorded normalised
      continue;
    }
    PatchSample p;
    p.id = ref.ids[k];
    const Vec3 rgb = kPlanted * ref.XYZ[k];
    p.mean = {rgb[0], rgb[1], rgb[2]};
    if (p.id == "A1") p.flags = {"saturated"};
    if (p.id == "A2") p.flags = {"dark"};
    if (p.id == "A3") p.flags = {"nonuniform"};
    if (p.id == "A4") p.flags = {"saturated", "dark"};
    s.patches.push_back(p);
  }
  return s;
}

Recipe cc24_recipe() {
  Recipe r;
  r.reference.chart = "cc24";
  r.sampling.layout.chart = "cc24";
  r.characterisation.model = "matrix-3x3";
  return r;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

}  // namespace

TEST_CASE("sample flags: the table names the flags sample_chart sets, saturated left out by default", "[recipe][flags]") {
  const std::vector<OptionSpec> t = sample_flag_table();
  REQUIRE(t.size() == 3);
  CHECK(t[0].name == "saturated");
  CHECK(t[1].name == "dark");
  CHECK(t[2].name == "nonuniform");
  for (const auto& o : t) {
    CHECK(o.type == "boolean");
    CHECK(!o.label.empty());
    CHECK(o.default_number == (o.name == "saturated" ? 1 : 0));
  }
}

TEST_CASE("sampling.exclude_flags leaves out the patches with those flags, and only those", "[recipe][flags][pair]") {
  const Recipe base = cc24_recipe();
  const ReferenceChart ref = recipe_reference(base);
  const ChartSample s = planted_sample(ref);

  // No rule: every sampled patch is used (23: D6 was not sampled), D6 named as outside the frame.
  const TrainingSet all = training_set(base, s, ref);
  CHECK(all.ids.size() == 23);
  CHECK(all.excluded == std::vector<std::string>{"D6 (outside the frame)"});
  CHECK(all.sampled);
  CHECK(all.missing == std::vector<std::string>{"D6"});

  Recipe sat = base;
  sat.sampling.exclude_flags = {"saturated"};
  const TrainingSet t = training_set(sat, s, ref);
  CHECK(t.ids.size() == 21);
  CHECK(!has(t.ids, "A1"));
  CHECK(!has(t.ids, "A4"));
  CHECK(has(t.ids, "A2"));  // dark only: kept
  CHECK(t.excluded == std::vector<std::string>{"A1 (saturated)", "A4 (saturated)", "D6 (outside the frame)"});

  // Every flag, listed in any order: completed to the table's order, the same set as exclude_flagged.
  Recipe every = base;
  every.sampling.exclude_flags = {"nonuniform", "saturated", "dark", "saturated"};
  CHECK(complete_recipe(every).sampling.exclude_flags == std::vector<std::string>{"saturated", "dark", "nonuniform"});
  Recipe flagged = base;
  flagged.sampling.exclude_flagged = true;
  const TrainingSet a = training_set(every, s, ref), b = training_set(flagged, s, ref);
  CHECK(a.ids.size() == 19);
  CHECK(a.ids == b.ids);
  CHECK(a.excluded == b.excluded);
  CHECK(has(a.excluded, "A4 (saturated, dark)"));

  // An unknown flag is refused naming it; a recipe without the rule writes no field for it.
  Recipe bad = base;
  bad.sampling.exclude_flags = {"glare"};
  require_code([&] { complete_recipe(bad); }, ErrorCode::UnknownId);
  require_code([&] { recipe_from_json(replaced(recipe_to_json(sat), "\"saturated\"", "\"glare\"")); },
               ErrorCode::UnknownId);
  const std::string plain = recipe_to_json(base), with = recipe_to_json(sat);
  CHECK(plain.find("exclude_flags") == std::string::npos);
  CHECK(plain.find("missing") == std::string::npos);
  CHECK(with.find("\"exclude_flags\": [\n      \"saturated\"\n    ]") != std::string::npos);
  CHECK(recipe_to_json(recipe_from_json(with)) == with);
}

TEST_CASE("a chart cut by the frame: the profile's recipe names the patches it was made without", "[recipe][cut][flags]") {
  Recipe r = cc24_recipe();
  r.sampling.exclude_flags = {"saturated"};
  const ReferenceChart ref = recipe_reference(r);
  const TrainingSet t = training_set(r, planted_sample(ref), ref);
  const Characterisation c = characterise(r, t);
  CHECK(c.recipe.sampling.missing == std::vector<std::string>{"D6"});
  // The planted 3×3 recovered (XYZ = M⁻¹ · RGB) from the 21 patches left.
  const Mat3 inverse = kPlanted.inverse();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) CHECK(c.evaluation.fit.model.coefficients(i, j) == Approx(inverse(i, j)).margin(1e-9));

  const std::string text = profile_to_json(c.profile);
  CHECK(text.find("\"missing\": [\n        \"D6\"\n      ]") != std::string::npos);
  const Profile back = profile_from_json(text);
  CHECK(back.recipe.sampling.missing == std::vector<std::string>{"D6"});

  // Fitted again from the profile's tables (a share link): the record is kept; sampled again on a
  // whole chart: it goes.
  const TrainingSet tables = training_set(back.recipe, back.training_labels, back.training_camera_RGB,
                                          back.training_reference_XYZ);
  CHECK(!tables.sampled);
  CHECK(profile_to_json(characterise(back.recipe, tables).profile) == text);
  ChartSample whole = planted_sample(ref);
  whole.missing.clear();
  CHECK(characterise(back.recipe, training_set(back.recipe, whole, ref)).recipe.sampling.missing.empty());
}

#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
#include "shell.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/io/json.hpp"

TEST_CASE("tristim models --json lists the layout option and sample flag tables as the engine has them", "[flags][cli]") {
  const json::Value all = json::parse(test::run_shell(std::string(TRISTIM_CLI) + " models --json"));
  CHECK(all.at("models").as_array().size() > 0);
  const auto same = [](const json::Value& listed, const std::vector<OptionSpec>& rows) {
    REQUIRE(listed.as_array().size() == rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      const json::Value& o = listed.as_array()[k];
      CHECK(o.at("name").as_string() == rows[k].name);
      CHECK(o.at("label").as_string() == rows[k].label);
      CHECK(o.at("type").as_string() == rows[k].type);
      CHECK(o.at("min").as_number() == rows[k].min);
      CHECK(o.at("max").as_number() == rows[k].max);
      CHECK(o.at("default_number").as_number() == rows[k].default_number);
      CHECK(o.at("step").as_number() == rows[k].step);
      CHECK(o.at("unit").as_string() == rows[k].unit);
    }
  };
  same(all.at("layout_options"), layout_option_table());
  same(all.at("sample_flags"), sample_flag_table());
}
#endif

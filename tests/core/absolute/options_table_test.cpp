// The Absolute mode's option rows against the engine functions that check them: the recipe's
// numbers and choices (absolute_option_table, complete_absolute_recipe) and the sensitivity
// estimate's (sensitivity_option_table, estimate_sensitivities_Jiang2013) — the page's inputs and
// `tristim absolute --help`. A row's default and bounds are accepted; a value past a bound, or a
// choice the row does not list, is refused with a coded error naming the option.
#include <cmath>
#include <map>
#include <string>

#include "test_support.hpp"
#include "tristim/absolute/options_table.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

template <class Table>
std::map<std::string, OptionSpec> by_name(Table table) {
  std::map<std::string, OptionSpec> m;
  for (const OptionSpec& o : table()) m[o.name] = o;
  return m;
}

/// The rows' names in order, each followed by a space.
std::string names_of(const std::vector<OptionSpec>& rows) {
  std::string names;
  for (const OptionSpec& o : rows) names += o.name + " ";
  return names;
}

/// `f()`'s error as "CODE: message", or "" when it returns.
template <class F>
std::string refusal(F f) {
  try {
    f();
  } catch (const Error& e) {
    return std::string(e.code_name()) + ": " + e.what();
  }
  return "";
}

/// The default recipe with number option `name` set to `value`.
AbsoluteRecipe with_number(const std::string& name, double value) {
  AbsoluteRecipe r;
  (name == "w" ? r.options.w : name == "noise_floor" ? r.options.noise_floor : r.options.saturation) = value;
  return r;
}

}  // namespace

TEST_CASE("absolute option table: its rows, and the recipe's defaults are the rows'", "[absolute][catalog]") {
  CHECK(names_of(absolute_option_table()) == "transform fusion w noise_floor saturation ");
  const auto rows = by_name(absolute_option_table);
  const AbsoluteOptions d;
  CHECK(rows.at("transform").default_text == d.transform);
  CHECK(rows.at("fusion").default_text == d.fusion);
  CHECK(rows.at("w").default_number == d.w);
  CHECK(rows.at("noise_floor").default_number == d.noise_floor);
  CHECK(rows.at("saturation").default_number == d.saturation);
  CHECK(rows.at("noise_floor").unit == "DN");
  CHECK(rows.at("saturation").unit == "DN");
  CHECK(refusal([] { complete_absolute_recipe(AbsoluteRecipe{}); }) == "");
}

TEST_CASE("absolute option table: complete_absolute_recipe refuses a number past a row's bounds", "[absolute][catalog]") {
  for (const auto& row : by_name(absolute_option_table)) {
    const std::string& name = row.first;  // not a structured binding: lambdas below capture it
    const OptionSpec& o = row.second;
    if (o.type != "number") continue;
    INFO(name);
    CHECK(refusal([&] { complete_absolute_recipe(with_number(name, o.max)); }) == "");
    // An exclusive minimum (w) is refused itself; an inclusive one accepted.
    const std::string at_min = refusal([&] { complete_absolute_recipe(with_number(name, o.min)); });
    if (o.min_exclusive) CHECK(at_min.rfind("INVALID_ARGUMENT: ", 0) == 0);
    else CHECK(at_min == "");
    for (double past : {o.min - 1, o.max * 1.001}) {
      INFO("value " << past);
      CHECK(refusal([&] { complete_absolute_recipe(with_number(name, past)); }).rfind("INVALID_ARGUMENT: ", 0) == 0);
    }
  }
  // w's lower bound is open (Z_u, Z_c, Z_o are disjoint only for w > 2, section 3.1): the row says
  // so (min_exclusive, which the page's box and --help show), and the next double above 2 is taken.
  const OptionSpec w = by_name(absolute_option_table).at("w");
  CHECK(w.min == 2);
  CHECK(w.min_exclusive);
  CHECK(refusal([] { complete_absolute_recipe(with_number("w", 2)); }).rfind("INVALID_ARGUMENT: ", 0) == 0);
  CHECK(refusal([] { complete_absolute_recipe(with_number("w", std::nextafter(2.0, 3.0))); }) == "");
  for (const auto& row : by_name(absolute_option_table)) CHECK(row.second.min_exclusive == (row.first == "w"));
}

TEST_CASE("absolute option table: a choice the row does not list is refused", "[absolute][catalog]") {
  const auto rows = by_name(absolute_option_table);
  for (const std::string& t : rows.at("transform").choices) {
    AbsoluteRecipe r;
    r.options.transform = t;
    CHECK(refusal([&] { complete_absolute_recipe(r); }) == "");
  }
  for (const std::string& f : rows.at("fusion").choices) {
    AbsoluteRecipe r;
    r.options.fusion = f;
    CHECK(refusal([&] { complete_absolute_recipe(r); }) == "");
  }
  AbsoluteRecipe t, f;
  t.options.transform = "T3";
  f.options.fusion = "median";
  CHECK(refusal([&] { complete_absolute_recipe(t); }).rfind("UNKNOWN_ID: ", 0) == 0);
  CHECK(refusal([&] { complete_absolute_recipe(f); }).rfind("UNKNOWN_ID: ", 0) == 0);
}

TEST_CASE("absolute sensitivity table: the recipe's sensitivities take exactly its ids", "[absolute][catalog]") {
  const std::vector<MethodInfo> table = absolute_sensitivity_table();
  std::string ids;
  for (const MethodInfo& m : table) {
    ids += m.id + " ";
    CHECK(!m.label.empty());
    CHECK(m.reference.find("Guarnera") != std::string::npos);  // eq (7)'s A_R, A_G, A_B
    CHECK(m.reference.find("eq (7)") != std::string::npos);
  }
  CHECK(ids == "none given camera ");
  // Each id with what it needs is accepted; the default recipe takes the first.
  CHECK(AbsoluteRecipe{}.inputs.sensitivities.choice == table.front().id);
  for (const MethodInfo& m : table) {
    INFO(m.id);
    AbsoluteRecipe r;
    r.inputs.sensitivities.choice = m.id;
    if (m.id == "camera") r.inputs.sensitivities.camera = "Nikon_D850";
    if (m.id == "given") {
      SpectralData ssf = camera_ssf("Nikon_D850");
      r.inputs.sensitivities.ssf = ssf;
    }
    CHECK(refusal([&] { complete_absolute_recipe(r); }) == "");
  }
  // Anything else is refused, the message listing the table's ids.
  for (const std::string bad : {"estimate", "", "None"}) {
    INFO("'" << bad << "'");
    AbsoluteRecipe r;
    r.inputs.sensitivities.choice = bad;
    const std::string why = refusal([&] { complete_absolute_recipe(r); });
    CHECK(why.rfind("INVALID_ARGUMENT: ", 0) == 0);
    CHECK(why.find("none, given, camera") != std::string::npos);
  }
}

TEST_CASE("sensitivity option table: estimate_sensitivities_Jiang2013 refuses K and μ past the rows' bounds",
          "[absolute][sensitivities][catalog]") {
  CHECK(names_of(sensitivity_option_table()) == "components smoothness ");
  const auto rows = by_name(sensitivity_option_table);
  const SensitivityOptions d;
  CHECK(rows.at("components").default_number == d.components);
  CHECK(rows.at("components").type == "integer");
  CHECK(rows.at("smoothness").default_number == d.smoothness);

  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData d65 = illuminant_spd("D65");
  const auto rgb = simulate_camera_RGB(camera_ssf("Nikon_D850"), refl, d65);
  auto estimate = [&](const std::string& name, double value) {
    SensitivityOptions o;
    if (name == "components") o.components = static_cast<int>(value);
    else o.smoothness = value;
    return refusal([&] { estimate_sensitivities_Jiang2013(rgb, refl, d65, o); });
  };
  for (const auto& [name, o] : rows) {
    INFO(name);
    for (double ok : {o.min, o.default_number, o.max}) {
      INFO("value " << ok);
      CHECK(estimate(name, ok) == "");
    }
    for (double past : {o.min - 1, o.max + 1}) {
      INFO("value " << past);
      const std::string why = estimate(name, past);
      CHECK(why.rfind("INVALID_ARGUMENT: ", 0) == 0);
      CHECK(why.find(name) != std::string::npos);
    }
  }
}

// The catalog's rows by their field lists (methods.hpp, models.hpp): every OptionSpec, MethodInfo,
// LinearisationListing, ModelInfo and ModelFamily the engine lists, written as `tristim models
// --json` / `tristim linearise --list` print them, reads back equal through the JSON text; unknown,
// missing and mistyped members are refused naming them.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/error.hpp"
#include "tristim/io/json.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/methods.hpp"
#include "tristim/profile/recipe.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {
const fields::Context kCtx{ErrorCode::InvalidArgument, "catalog: "};

/// `value` written by its list, to text and back, read by the same list.
template <class T>
T round_trip(const T& value) { T out{}; fields::read(json::parse(fields::write(value).dump(2)), out, kCtx); return out; }

void check_same(const OptionSpec& a, const OptionSpec& b) {
  INFO("option " << a.name);
  CHECK(a.name == b.name);
  CHECK(a.type == b.type);
  CHECK(a.label == b.label);
  CHECK(a.default_number == b.default_number);
  CHECK(a.default_text == b.default_text);
  CHECK(a.min == b.min);
  CHECK(a.max == b.max);
  CHECK(a.choices == b.choices);
  CHECK(a.description == b.description);
  CHECK(a.step == b.step);
  CHECK(a.unit == b.unit);
  CHECK(a.min_exclusive == b.min_exclusive);
}
void check_same(const std::vector<OptionSpec>& a, const std::vector<OptionSpec>& b) {
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) check_same(a[i], b[i]);
}

/// A method row's members (MethodInfo, LinearisationListing).
template <class Row>
void check_row(const Row& b, const Row& a) {
  INFO("row " << a.id);
  CHECK((b.id == a.id && b.label == a.label && b.reference == a.reference));
  check_same(b.options, a.options);
}

/// A row with every member set away from its default (a choice with a unit and an exclusive min).
OptionSpec full_row() {
  OptionSpec o = number_option("w", "Width", 2.5, 2, 40, "the window's width, in pixels");
  o.choices = {"a", "b"};
  o.default_text = "b";
  o.step = 0.5;
  o.unit = "px";
  o.min_exclusive = true;
  return o;
}
}  // namespace

TEST_CASE("catalog fields: every option row the engine lists reads back equal", "[catalog][option][fields]") {
  check_same(round_trip(full_row()), full_row());
  std::vector<std::vector<OptionSpec>> tables = {layout_option_table(), sample_flag_table()};
  for (const auto& m : method_infos(objective_table())) tables.push_back(m.options);
  for (const auto& m : flat_field_methods()) tables.push_back(m.options);
  for (const auto& s : surface_listing()) tables.push_back(s.options);
  size_t rows = 0;
  for (const auto& t : tables) {
    check_same(round_trip(t), t);
    rows += t.size();
  }
  CHECK(rows > 5);
  // The JSON names are the C++ names, in declaration order.
  const json::Value o = fields::write(full_row());
  std::vector<std::string> names;
  for (const auto& [k, v] : o.members()) names.push_back(k);
  CHECK(names == std::vector<std::string>{"name", "type", "label", "default_number", "default_text", "min", "max",
                                          "choices", "description", "step", "unit", "min_exclusive"});
  CHECK(o.at("min_exclusive").as_bool());
}

TEST_CASE("catalog fields: method, linearisation and model rows read back equal", "[catalog][models][lineari][fields]") {
  for (const auto& m : method_infos(objective_table())) check_row(round_trip(m), m);
  const auto listing = linearisation_listing();
  REQUIRE(listing.size() > 3);
  for (const auto& l : listing) {
    const LinearisationListing b = round_trip(l);
    check_row(b, l);
    CHECK((b.needs == l.needs && b.needs_text == l.needs_text));
  }
  for (const auto& m : model_table()) {
    INFO("model " << m.id);
    const ModelInfo b = round_trip(m);
    CHECK((b.id == m.id && b.label == m.label && b.reference == m.reference && b.n_terms == m.n_terms));
    CHECK(b.term_names == m.term_names);
    REQUIRE(b.terms.size() == m.terms.size());
    for (size_t i = 0; i < m.terms.size(); ++i)
      CHECK((b.terms[i].r == m.terms[i].r && b.terms[i].g == m.terms[i].g && b.terms[i].b == m.terms[i].b));
    CHECK((b.root == m.root && b.linear == m.linear && b.exposure_invariant == m.exposure_invariant));
    CHECK((b.duplicate_of == m.duplicate_of && b.family == m.family));
  }
  for (const auto& f : model_families()) {
    const ModelFamily b = round_trip(f);
    CHECK((b.id == f.id && b.label == f.label && b.about == f.about));
  }
}

TEST_CASE("catalog fields: unknown, missing and mistyped members are refused", "[catalog][option][fields]") {
  const json::Value good = fields::write(full_row());
  auto read_with = [&](const char* name, const json::Value& v) {
    json::Value o = good;
    o.set(name, v);
    OptionSpec out;
    fields::read(o, out, kCtx);
  };
  require_code([&] { read_with("maximum", 3); }, ErrorCode::InvalidArgument);
  CHECK_THROWS_WITH(read_with("maximum", 3), "catalog: unknown field 'maximum'");
  require_code([&] { read_with("min_exclusive", 1); }, ErrorCode::InvalidArgument);
  CHECK_THROWS_WITH(read_with("min", "2"), Catch::Matchers::Contains("'min'"));
  CHECK_THROWS_WITH(read_with("choices", "a"), Catch::Matchers::Contains("'choices'"));
  // A bound that is not a number is written null: refused by a strict reader, NaN where null is NaN (JS).
  OptionSpec nan_bound = full_row();
  nan_bound.max = std::nan("");
  const json::Value written = json::parse(fields::write(nan_bound).dump());
  CHECK(written.at("max").is_null());
  OptionSpec back;
  require_code([&] { fields::read(written, back, kCtx); }, ErrorCode::InvalidArgument);
  fields::Context js = kCtx;
  js.null_is_nan = true;
  fields::read(written, back, js);
  CHECK(std::isnan(back.max));
  // A member left out is refused; nested: an option row inside a method row names its path.
  json::Value missing = json::Value::object();
  for (const auto& [k, v] : good.members())
    if (k != "label") missing.set(k, v);
  OptionSpec out;
  CHECK_THROWS_WITH(fields::read(missing, out, kCtx), "catalog: missing field 'label'");
  MethodInfo info{"x", "X", "none", {full_row()}};
  json::Value mi = fields::write(info);
  json::Value opts = json::Value::array();
  json::Value row = good;
  row.set("colour", 1);
  opts.push(row);
  mi.set("options", opts);
  MethodInfo mi_out;
  CHECK_THROWS_WITH(fields::read(mi, mi_out, kCtx), "catalog: unknown field 'options[0].colour'");
}

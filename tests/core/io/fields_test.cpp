// io/fields.hpp: a struct declared once as a field list gives its JSON writer and strict reader —
// planted values written and read back exactly, members in list order, unknown and missing
// members refused with the reader's code naming the dotted path, optional members keeping the C++
// default, the short form (write_picked), tables as rows, null as NaN only where asked for, and
// the versioned document rules.
#include <cmath>
#include <functional>
#include <string>

#include "test_support.hpp"
#include "tristim/io/fields.hpp"

using namespace tristim;

namespace {
struct Inner {
  std::array<double, 3> triple{1, 2, 3};
  bool flag = false;
};
struct Outer {
  std::string name = "default";
  int count = 7;
  double level = 0.5;
  Inner inner;
  std::vector<std::string> tags;
  Eigen::Vector3d white = Eigen::Vector3d(0.9642, 1, 0.8251);
  std::map<std::string, double> extra;  // optional
  Eigen::MatrixXd matrix = Eigen::MatrixXd::Identity(2, 3);
};
}  // namespace

namespace tristim::fields {
TRISTIM_FIELDS(Inner, member<&Inner::triple>("triple"), member<&Inner::flag>("flag"));
TRISTIM_FIELDS(Outer, member<&Outer::name>("name"), member<&Outer::count>("count"), member<&Outer::level>("level"),
               member<&Outer::inner>("inner"), member<&Outer::tags>("tags"), member<&Outer::white>("white"),
               member<&Outer::extra>("extra", false), member<&Outer::matrix>("matrix"));
}  // namespace tristim::fields

namespace {
const fields::Context kCtx{ErrorCode::RecipeInvalid, "thing: "};

Outer planted() {
  Outer o;
  o.name = "planted \"quoted\"";
  o.count = -12;
  o.level = 0.1 + 0.2;  // not a short decimal: the round trip must be exact
  o.inner.triple = {1e-300, -0.0, 3.5};
  o.inner.flag = true;
  o.tags = {"A1", "B2"};
  o.white = Eigen::Vector3d(95.047, 100, 108.883);
  o.extra = {{"k", 2.5}};
  o.matrix.resize(2, 2);
  o.matrix << 1, 2, 3, 4;
  return o;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// `v` without the member `key`.
json::Value without(const json::Value& v, const std::string& key) {
  json::Value out = json::Value::object();
  for (const auto& [k, x] : v.members())
    if (k != key) out.set(k, x);
  return out;
}
}  // namespace

TEST_CASE("fields: a planted struct is written in list order and read back exactly", "[io][fields]") {
  const Outer o = planted();
  const std::string text = fields::write(o).dump();
  CHECK(text.find("{\"name\":") == 0);
  CHECK(text.find("\"count\":-12,\"level\":") != std::string::npos);
  CHECK(text.find("\"matrix\":[[1,2],[3,4]]") != std::string::npos);
  Outer back;
  fields::read(json::parse(text), back, kCtx);
  CHECK(back.name == o.name);
  CHECK(back.count == o.count);
  CHECK(back.level == o.level);
  CHECK(back.inner.triple == o.inner.triple);
  CHECK(std::signbit(back.inner.triple[1]));
  CHECK(back.inner.flag);
  CHECK(back.tags == o.tags);
  CHECK(back.white == o.white);
  CHECK(back.extra == o.extra);
  CHECK(back.matrix == o.matrix);
  CHECK(fields::write(back).dump() == text);
}

TEST_CASE("fields: unknown, missing and mistyped members are refused naming their path", "[io][fields]") {
  const json::Value v = fields::write(planted());
  Outer out;
  json::Value unknown = v;
  json::Value inner = *unknown.find("inner");
  inner.set("colour", 1);
  unknown.set("inner", inner);
  test::require_code([&] { fields::read(unknown, out, kCtx); }, ErrorCode::RecipeInvalid);
  CHECK(message_of([&] { fields::read(unknown, out, kCtx); }) == "thing: unknown field 'inner.colour'");
  CHECK(message_of([&] { fields::read(without(v, "level"), out, kCtx); }) == "thing: missing field 'level'");

  json::Value wrong = v;
  wrong.set("count", 1.5);
  CHECK(message_of([&] { fields::read(wrong, out, kCtx); }) == "thing: 'count' must be an integer");
  wrong = v;
  wrong.set("tags", json::Value(std::vector<double>{1}));
  CHECK(message_of([&] { fields::read(wrong, out, kCtx); }) == "thing: 'tags[0]' must be a string");
  wrong = v;
  json::Value short_triple = *wrong.find("inner");
  short_triple.set("triple", json::Value(std::vector<double>{1, 2}));
  wrong.set("inner", short_triple);
  CHECK(message_of([&] { fields::read(wrong, out, kCtx); }) == "thing: 'inner.triple' must have 3 elements");
  test::require_code([&] { fields::read(json::parse("[]"), out, kCtx); }, ErrorCode::RecipeInvalid);
}

TEST_CASE("fields: an optional member left out keeps its C++ default, null reads as NaN only when asked", "[io][fields]") {
  const json::Value v = fields::write(planted());
  Outer out;
  out.extra = {{"kept", 1}};
  fields::read(without(v, "extra"), out, kCtx);
  CHECK(out.extra == std::map<std::string, double>{{"kept", 1}});

  json::Value with_null = v;
  with_null.set("level", json::Value());
  test::require_code([&] { fields::read(with_null, out, kCtx); }, ErrorCode::RecipeInvalid);
  fields::Context lenient = kCtx;
  lenient.null_is_nan = true;
  fields::read(with_null, out, lenient);
  CHECK(std::isnan(out.level));
}

TEST_CASE("fields: the short form, tables as rows and versioned documents", "[io][fields]") {
  CHECK(fields::write_picked(planted(), {"level", "name"}).dump() ==
        "{\"level\":0.30000000000000004,\"name\":\"planted \\\"quoted\\\"\"}");
  const std::vector<std::string> ids{"A1", "B2"};
  const std::vector<double> values{0.5, NAN};
  CHECK(fields::rows({{"patch", ids}, {"value", values}}).dump() ==
        "[{\"patch\":\"A1\",\"value\":0.5},{\"patch\":\"B2\",\"value\":null}]");

  const fields::Document d{"tristim-thing", 3, "thing", ErrorCode::RecipeInvalid, ErrorCode::RecipeVersion};
  const json::Value doc = fields::write_document(planted(), d);
  CHECK(doc.dump().find("{\"format\":\"tristim-thing\",\"version\":3,\"name\":") == 0);
  Outer back;
  fields::read_document(doc, back, d, kCtx);
  CHECK(back.level == planted().level);
  json::Value other = doc;
  other.set("version", 4);
  test::require_code([&] { fields::check_document(other, d); }, ErrorCode::RecipeVersion);
  other.set("format", "tristim-other");
  test::require_code([&] { fields::check_document(other, d); }, ErrorCode::RecipeInvalid);
  test::require_code([&] { fields::parse_document("{\"format\":", d); }, ErrorCode::RecipeInvalid);
}

// ChartFigures' field list (profile/characterise.hpp): the per-chart figures of a fit on several
// charts, as `tristim fit` writes them in the profile's "charts" and the page gets them, written
// and read back equal; an unknown or missing member refused naming it.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "tristim/error.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/profile.hpp"

using namespace tristim;

namespace {

const fields::Context kContext{ErrorCode::ProfileInvalid, "charts: "};

std::vector<ChartFigures> planted() {
  ChartFigures a;  // every figure
  a.name = "cc24.dng";
  a.patches = 24;
  a.training_dE00.mean = 0.375;
  a.training_dE00.max = 1.8453590335541079;
  a.has_loo = true;
  a.loo_dE00.mean = 0.39134594580199;
  a.loo_dE00.max = 1.875;
  a.has_held_out = true;
  a.held_out_dE00.mean = 0.5;
  a.held_out_dE00.max = 5.5;
  ChartFigures b;  // no leave-one-out, no held-out figure
  b.name = "sg140.dng #2";
  b.patches = 3;
  b.training_dE00.mean = 1.25;
  b.training_dE00.max = 2.5;
  b.held_out_error = "TOO_FEW_PATCHES: 3 patches for 10 terms";
  ChartFigures c;  // a chart without patches: no figure at all
  c.name = "empty";
  return {a, b, c};
}

bool same_mean_max(const Summary& x, const Summary& y) { return x.mean == y.mean && x.max == y.max; }

std::string refusal(const std::string& text) {
  try {
    std::vector<ChartFigures> out;
    fields::read(json::parse(text), out, kContext, "charts");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::ProfileInvalid);
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST_CASE("chart figures: written as tristim fit writes them, read back equal", "[profile][chart][fields]") {
  const std::vector<ChartFigures> f = planted();
  const json::Value j = fields::write(f);
  CHECK(j.dump() ==
        "[{\"chart\":\"cc24.dng\",\"patches\":24,"
        "\"training\":{\"dE00_mean\":0.375,\"dE00_max\":1.8453590335541079},"
        "\"loo\":{\"dE00_mean\":0.39134594580199,\"dE00_max\":1.875},"
        "\"held_out\":{\"dE00_mean\":0.5,\"dE00_max\":5.5},\"held_out_error\":\"\"},"
        "{\"chart\":\"sg140.dng #2\",\"patches\":3,\"training\":{\"dE00_mean\":1.25,\"dE00_max\":2.5},"
        "\"loo\":null,\"held_out\":null,\"held_out_error\":\"TOO_FEW_PATCHES: 3 patches for 10 terms\"},"
        "{\"chart\":\"empty\",\"patches\":0,\"training\":null,\"loo\":null,\"held_out\":null,\"held_out_error\":\"\"}]");

  std::vector<ChartFigures> back;
  fields::read(json::parse(j.dump(2)), back, kContext, "charts");
  REQUIRE(back.size() == f.size());
  for (size_t k = 0; k < f.size(); ++k) {
    INFO(f[k].name);
    CHECK(back[k].name == f[k].name);
    CHECK(back[k].patches == f[k].patches);
    CHECK(same_mean_max(back[k].training_dE00, f[k].training_dE00));
    CHECK(back[k].has_loo == f[k].has_loo);
    CHECK(same_mean_max(back[k].loo_dE00, f[k].loo_dE00));
    CHECK(back[k].has_held_out == f[k].has_held_out);
    CHECK(same_mean_max(back[k].held_out_dE00, f[k].held_out_dE00));
    CHECK(back[k].held_out_error == f[k].held_out_error);
  }
  CHECK(fields::write(back).dump() == j.dump());
}

TEST_CASE("chart figures: an unknown, missing or mistyped member is refused naming it", "[profile][chart][fields]") {
  const std::string ok = "{\"chart\":\"a\",\"patches\":1,\"training\":{\"dE00_mean\":1,\"dE00_max\":2},"
                         "\"loo\":null,\"held_out\":null,\"held_out_error\":\"\"";
  CHECK(refusal("[" + ok + "}]") == "(read)");
  CHECK(refusal("[" + ok + ",\"extra\":1}]") == "charts: unknown field 'charts[0].extra'");
  CHECK(refusal("[{\"chart\":\"a\",\"patches\":1,\"training\":{\"dE00_mean\":1,\"dE00_median\":1,\"dE00_max\":2},"
                "\"loo\":null,\"held_out\":null,\"held_out_error\":\"\"}]") ==
        "charts: unknown field 'charts[0].training.dE00_median'");
  CHECK(refusal("[{\"chart\":\"a\",\"patches\":1,\"training\":{\"dE00_mean\":1},"
                "\"loo\":null,\"held_out\":null,\"held_out_error\":\"\"}]") ==
        "charts: missing field 'charts[0].training.dE00_max'");
  CHECK(refusal("[{\"chart\":\"a\",\"patches\":1,\"training\":null,\"loo\":null,\"held_out\":null}]") ==
        "charts: missing field 'charts[0].held_out_error'");
  CHECK(refusal("[{\"chart\":\"a\",\"patches\":1,\"training\":null,\"loo\":3,\"held_out\":null,\"held_out_error\":\"\"}]") ==
        "charts: 'charts[0].loo' must be an object");
}

TEST_CASE("a profile's \"charts\" are read by ChartFigures' list: an unknown member refused", "[profile][chart][fields]") {
  PatchMatrix rgb(12, 3);
  for (int i = 0; i < 12; ++i) rgb.row(i) << 0.05 + 0.07 * i, 0.9 - 0.06 * i, 0.1 + 0.03 * (i % 5);
  const PatchMatrix xyz = rgb * Eigen::Matrix3d::Identity() * 0.8;
  std::vector<std::string> ids;
  for (int i = 0; i < 12; ++i) ids.push_back("P" + std::to_string(i + 1));
  const FitOptions o;
  json::Value doc = profile_json(make_profile(evaluate_model("matrix-3x3", rgb, xyz, o), o, ids, rgb, xyz));
  doc.set("charts", fields::write(planted()));
  CHECK(profile_from_document(doc).model.id == "matrix-3x3");
  CHECK(profile_from_json(doc.dump(2)).model.id == "matrix-3x3");

  json::Value bad = fields::write(planted());
  json::Value row = bad.as_array()[1];
  row.set("has_loo", false);  // the C++ name, which the JSON does not use
  json::Value rows = json::Value::array();
  rows.push(row);
  doc.set("charts", rows);
  try {
    profile_from_document(doc);
    FAIL("read");
  } catch (const Error& e) {
    CHECK(e.code() == ErrorCode::ProfileInvalid);
    CHECK(std::string(e.what()) == "unknown field 'charts[0].has_loo'");
  }
}

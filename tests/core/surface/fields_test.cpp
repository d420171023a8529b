// The surface stage's results by their field lists (surface/fields.cpp): a Table IV cell written
// and read back exactly (the fitted correction through its --surface text), unknown and malformed
// members refused with a code; a Phase I result's JSON carries its figures, rows and — when the
// result holds them — its spectra.
#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/geometry_table.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;

namespace {

const fields::Context strict{ErrorCode::InvalidArgument, "cell: "};

GeometryTableCell planted_cell(const std::string& method, bool ok) {
  GeometryTableCell c;
  c.training = "SG";
  c.method = method;
  c.ok = ok;
  c.error_code = ok ? "" : "ILL_POSED";
  c.message = ok ? "" : "a white RGB of zero";
  c.dE_xyz = summarize({0.011, 0.0043, 0.027, 0.1 / 3});
  c.dE00 = summarize({1.25, 0.5, 2.0 / 3, 3.75, 0.1});
  c.correction = parse_choice("saunderson:k1=0.04,k2=0.6,k_ins=0,k1_capture=0.0552092313303770,k2_capture=0.6,k_ins_capture=0.3");
  c.mu = method == "corrected-3x3" ? 0.9312345678901234 : 0;
  c.status = ok ? "at_bound" : "";
  return c;
}

}  // namespace

TEST_CASE("surface fields: a Table IV cell round-trips through its JSON exactly", "[surface][fields]") {
  for (const auto& [method, ok] : {std::pair<std::string, bool>{"saunderson", true}, {"corrected-3x3", true},
                                   {"scaler-offset", false}}) {
    INFO(method << (ok ? "" : " (failed)"));
    const GeometryTableCell c = planted_cell(method, ok);
    const json::Value j = fields::write(c);
    CHECK((j.find("error_code") != nullptr) == !ok);     // written only for a failed cell
    CHECK((j.find("mu") != nullptr) == (method == "corrected-3x3"));
    CHECK(j.at("surface").as_string() == surface_choice_text(c.correction));
    GeometryTableCell back;
    fields::read(json::parse(j.dump(2)), back, strict);
    CHECK(back.training == c.training);
    CHECK(back.method == c.method);
    CHECK(back.ok == c.ok);
    CHECK(back.error_code == c.error_code);
    CHECK(back.message == c.message);
    CHECK(fields::write(back.dE_xyz).dump() == fields::write(c.dE_xyz).dump());  // every member, 17 digits
    CHECK(fields::write(back.dE00).dump() == fields::write(c.dE00).dump());
    CHECK(back.correction.method == c.correction.method);
    CHECK(back.correction.parameters == c.correction.parameters);  // to the bit, through the text
    CHECK(back.mu == c.mu);
    CHECK(back.status == c.status);
    CHECK(fields::write(back).dump(2) == j.dump(2));
  }
}

TEST_CASE("surface fields: a cell's unknown or malformed members are refused, naming them", "[surface][fields]") {
  const json::Value j = fields::write(planted_cell("saunderson", true));
  auto with = [&](const char* name, json::Value v) {
    json::Value o = j;
    o.set(name, std::move(v));
    return o;
  };
  auto refused = [](const json::Value& o, const std::string& named) {
    GeometryTableCell c;
    try {
      fields::read(o, c, strict);
    } catch (const Error& e) {
      CHECK(std::string(error_code_name(e.code())) == error_code_name(ErrorCode::InvalidArgument));
      CHECK_THAT(e.what(), Catch::Contains(named));
      return;
    }
    FAIL("expected a coded error naming " << named);
  };
  refused(with("shiny", 1), "unknown field 'shiny'");
  refused(with("ok", "yes"), "'ok'");
  refused(with("surface", "kubelka-munk:k=1"), "'surface'");
  json::Value summary = j.at("dE00");
  summary.set("n", 5);
  refused(with("dE00", summary), "unknown field 'dE00.n'");
  json::Value missing = json::Value::object();
  for (const auto& [k, v] : j.members())
    if (k != "training") missing.set(k, v);
  refused(missing, "missing field 'training'");
}

TEST_CASE("surface fields: a Phase I result's JSON (figures, rows, spectra when held)", "[surface][fields]") {
  const SpectralData base = read_spectral_csv(
      test::read_test_file("core/data/charts/colorcheckerSG_before_nov2014_reflectance_380-730_10nm.csv"), "SG");
  SurfaceFitOptions o;
  o.range_min = 400;
  o.range_max = 700;
  const SurfaceFitResult r =
      fit_surface({"scaler-offset", {}, {}}, base, correct_surface(parse_choice("scaler-offset:mu=0.95,rho=0.03"), base), o);
  const json::Value j = fields::write(r);
  CHECK(j.at("method").as_string() == "scaler-offset");
  CHECK(j.at("surface").as_string() == surface_choice_text(r.choice));
  CHECK(j.at("range_nm").as_numbers("range_nm") == std::vector<double>{400, 700});
  CHECK(j.at("illuminant").as_string() == "D50");
  CHECK(j.at("observer").as_string() == "1931");
  CHECK(j.at("spectral_rms").at("after").as_number() == r.spectral_rms_after);
  CHECK(j.at("dE00").at("after").dump() == fields::write(r.summary_dE00_after).dump());
  const auto& rows = j.at("patches").as_array();
  REQUIRE(rows.size() == r.ids.size());
  CHECK(rows[17].at("patch").as_string() == r.ids[17]);
  CHECK(rows[17].at("dE00_after").as_number() == r.dE00_after[17]);
  REQUIRE(j.find("corrected") != nullptr);
  CHECK(j.at("corrected").at("values").as_array()[17].as_numbers("values") == r.corrected.values[17]);
  CHECK(j.at("target").at("names").as_array()[17].as_string() == r.ids[17]);

  SurfaceFitResult printed = r;  // the CLI's form: no spectra
  printed.measured = printed.corrected = printed.target = SpectralData{};
  const json::Value p = fields::write(printed);
  CHECK(p.find("measured") == nullptr);
  CHECK(p.find("corrected") == nullptr);
  CHECK(p.find("target") == nullptr);
  // Derived members (the --surface text, range_nm) are written only: reading one is refused.
  SurfaceFitResult back;
  test::require_code([&] { fields::read(p, back, strict); }, ErrorCode::InvalidArgument);
}

TEST_CASE("surface fields: a Phase II result's matrix is row-major", "[surface][fields]") {
  JointFitResult r;
  r.choice = parse_choice("scaler-offset:mu=1.04,rho=-0.02");
  r.matrix << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  const json::Value j = fields::write(r);
  CHECK(j.at("matrix").as_numbers("matrix") == std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK(j.at("surface").as_string() == "scaler-offset:mu=1.04,rho=-0.02");
  std::vector<std::string> names;
  for (const auto& [k, v] : j.members()) names.push_back(k);
  CHECK(names == std::vector<std::string>{"choice", "surface", "matrix", "dE_xyz_rms_start", "dE_xyz_rms", "status",
                                          "message", "evaluations"});
}

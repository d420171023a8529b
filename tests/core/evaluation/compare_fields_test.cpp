// The compare table's structs by their field lists (evaluation.hpp): a CompareRow, a RidgeRow, a
// StoppingCheck and a TransferCell written as `tristim compare --json` prints them read back equal,
// through the JSON text; unknown, missing and misspelt members are refused.
#include <string>
#include <vector>

#include "synthetic.hpp"
#include "test_support.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {
const fields::Context kCtx{ErrorCode::InvalidArgument, "compare row: "};

/// `value` written by its list, to text and back, read by the same list.
template <class T>
T round_trip(const T& value) {
  T out{};
  fields::read(json::parse(fields::write(value).dump(2)), out, kCtx);
  return out;
}

void check_same(const Summary& a, const Summary& b) {
  CHECK(a.min == b.min);
  CHECK(a.median == b.median);
  CHECK(a.mean == b.mean);
  CHECK(a.p95 == b.p95);
  CHECK(a.max == b.max);
  CHECK(a.rms == b.rms);
  CHECK(a.std == b.std);
}
void check_same(const CompareRow& a, const CompareRow& b) {
  INFO(a.model_id << " " << objective_id(a.objective));
  CHECK(a.model_id == b.model_id);
  CHECK(a.objective == b.objective);
  CHECK(a.n_terms == b.n_terms);
  CHECK(a.ok == b.ok);
  CHECK(a.error_code == b.error_code);
  CHECK(a.message == b.message);
  CHECK(a.status == b.status);
  CHECK(a.condition_number == b.condition_number);
  CHECK(a.seconds == b.seconds);
  CHECK(a.cpu_seconds == b.cpu_seconds);
  check_same(a.train_dE00, b.train_dE00);
  check_same(a.loo_dE00, b.loo_dE00);
  check_same(a.train_dE_xyz, b.train_dE_xyz);
  check_same(a.loo_dE_xyz, b.loo_dE_xyz);
  CHECK(a.has_loo == b.has_loo);
}

std::vector<std::string> names_of(const json::Value& o) {
  std::vector<std::string> names;
  for (const auto& m : o.members()) names.push_back(m.first);
  return names;
}

/// A 3x3 matrix's XYZ of 22 patches, with a little of each channel's error: rows that fit, one
/// exactly determined without leave-one-out (22 terms), one refused (35 terms).
struct Planted {
  PatchMatrix rgb = test::random_patches(22, 5, 0.03, 0.9), xyz;
  Planted() {
    Model truth{"matrix-3x3", Eigen::Matrix3d()};
    truth.coefficients << 40, 30, 15, 20, 70, 8, 2, 10, 90;
    xyz = predict(truth, rgb);
    for (Eigen::Index i = 0; i < xyz.rows(); ++i) xyz(i, static_cast<int>(i % 3)) *= 1.0 + 0.01 * static_cast<double>(i % 5);
  }
};
}  // namespace

TEST_CASE("compare fields: a CompareRow written by its list reads back equal", "[evaluation][compare][fields]") {
  const Planted p;
  const auto rows = compare_models(p.rgb, p.xyz, {}, {"matrix-3x3", "Finlayson2015-4", "Cheung2004-35"},
                                   {Objective::LeastSquares, Objective::DeltaE2000});
  REQUIRE(rows.size() == 6);
  bool refused = false, without_loo = false, not_ok_status = false;
  for (const CompareRow& r : rows) {
    check_same(r, round_trip(r));
    refused = refused || !r.ok;
    without_loo = without_loo || (r.ok && !r.has_loo);
    not_ok_status = not_ok_status || (r.ok && r.status != FitStatus::Ok);
  }
  CHECK(refused);
  CHECK(without_loo);
  CHECK(not_ok_status);
  // The members and their order are tristim compare --json's; leave-one-out only when there is one.
  const std::vector<std::string> all = {"model", "objective", "n_terms", "ok", "error_code", "status", "message",
                                        "condition_number", "seconds", "cpu_seconds", "train_dE00", "train_dE_xyz",
                                        "has_loo", "loo_dE00", "loo_dE_xyz"};
  for (const CompareRow& r : rows) {
    const json::Value o = fields::write(r);
    std::vector<std::string> want = all;
    if (!r.has_loo) want.resize(want.size() - 2);
    CHECK(names_of(o) == want);
    CHECK(o.at("model").as_string() == r.model_id);
    CHECK(o.at("objective").as_string() == objective_id(r.objective));
    CHECK(o.at("status").as_string() == (r.ok ? fit_status_name(r.status) : "error"));
  }
}

TEST_CASE("compare fields: unknown, missing and misspelt members are refused", "[evaluation][compare][fields]") {
  const Planted p;
  const CompareRow r = compare_models(p.rgb, p.xyz, {}, {"matrix-3x3"}, {Objective::LeastSquares}).at(0);
  const json::Value good = fields::write(r);
  auto read_with = [&](const char* name, const json::Value& v) {
    json::Value o = good;
    o.set(name, v);
    CompareRow out;
    fields::read(o, out, kCtx);
  };
  auto message_of = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  require_code([&] { read_with("colour", 1); }, ErrorCode::InvalidArgument);
  CHECK(message_of([&] { read_with("colour", 1); }) == "compare row: unknown field 'colour'");
  require_code([&] { read_with("objective", "steepest"); }, ErrorCode::InvalidArgument);
  CHECK(message_of([&] { read_with("objective", "steepest"); }).find("'objective'") != std::string::npos);
  require_code([&] { read_with("status", "fine"); }, ErrorCode::InvalidArgument);
  require_code([&] { read_with("n_terms", 2.5); }, ErrorCode::InvalidArgument);
  json::Value no_objective = json::Value::object();
  for (const auto& [k, v] : good.members())
    if (k != "objective") no_objective.set(k, v);
  CompareRow out;
  CHECK(message_of([&] { fields::read(no_objective, out, kCtx); }) == "compare row: missing field 'objective'");
  // A ridge row is marked "ridge": true; a compare row does not read as one without it, nor with false.
  RidgeRow ridge;
  json::Value marked = good;
  marked.set("lambda", 0.5);
  require_code([&] { fields::read(marked, out, kCtx); }, ErrorCode::InvalidArgument);
  marked.set("ridge", false);
  require_code([&] { fields::read(marked, ridge, kCtx); }, ErrorCode::InvalidArgument);
}

TEST_CASE("compare fields: ridge rows, stopping checks and transfer cells read back equal", "[evaluation][compare][ridge][stopping][transfer][fields]") {
  const Planted p;
  for (const char* id : {"Finlayson2015-2", "Cheung2004-35"}) {
    const RidgeRow r = ridge_row(id, p.rgb, p.xyz);
    const RidgeRow back = round_trip(r);
    check_same(r.row, back.row);
    CHECK(r.lambda == back.lambda);
    const json::Value o = fields::write(r);
    CHECK(o.at("ridge").as_bool());
    CHECK(names_of(o).back() == "lambda");
  }
  FitOptions de;
  de.objective = Objective::DeltaE2000;
  const ModelEvaluation ev = evaluate_model("Finlayson2015-2", p.rgb, p.xyz, de);
  const StoppingCheck s =
      leave_one_out_stopping_check("Finlayson2015-2", p.rgb, p.xyz, de, -1, ev.loo.dE00.mean, ev.fit.condition_number, 0);
  REQUIRE(s.checked);
  const StoppingCheck t = round_trip(s);
  CHECK(t.checked == s.checked);
  CHECK(t.flagged == s.flagged);
  CHECK(t.loo_mean == s.loo_mean);
  CHECK(t.perturbed_loo_mean == s.perturbed_loo_mean);
  const auto cells = transfer_table({{"A", p.rgb, p.xyz}}, p.rgb.topRows(10), p.xyz.topRows(10),
                                    {"matrix-3x3", "Cheung2004-35"}, {Objective::LeastSquares});
  REQUIRE(cells.size() == 2);
  CHECK_FALSE(cells[1].ok);
  for (const TransferCell& c : cells) {
    const TransferCell b = round_trip(c);
    CHECK(b.training_set == c.training_set);
    CHECK(b.model_id == c.model_id);
    CHECK(b.objective == c.objective);
    CHECK(b.ok == c.ok);
    CHECK(b.error_code == c.error_code);
    CHECK(b.message.empty());  // not in the CLI's cells, so not in the list
    check_same(b.dE_xyz, c.dE_xyz);
    check_same(b.dE00, c.dE00);
  }
}

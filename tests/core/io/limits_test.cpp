// Resource limits (io/limits.hpp, issue 14): the four cases found by hand end at once with
// LIMIT_EXCEEDED — a 1,000,000-row patch table (fit and evaluate read it the same way), a 32 MB
// profile whose bulk is an array the reader ignores, an 87 MB profile — and every other limit
// is checked just past its value. Inputs are made at test time. Elapsed times are printed.
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

#include "test_support.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/profile.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {

/// Runs f, expects LIMIT_EXCEEDED, prints how long it took to say so.
void expect_limit(const std::string& what, const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  require_code(f, ErrorCode::LimitExceeded);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("limits: %s -> LIMIT_EXCEEDED in %.3f s\n", what.c_str(), s);
}

std::string patch_rows(std::size_t n, const char* header) {
  std::string t = header;
  t.reserve(n * 24 + 32);
  char buf[64];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "P%zu,%zu,%zu,%zu\n", i + 1, i % 997 + 1, i % 991 + 1, i % 983 + 1);
    t += buf;
  }
  return t;
}

std::string small_profile_json() {
  PatchMatrix rgb(12, 3), xyz(12, 3);
  for (int i = 0; i < 12; ++i) {
    rgb.row(i) << 10 + 7 * i, 20 + 3 * (i % 5), 5 + 11 * (i % 4);
    xyz.row(i) << 0.4 * rgb(i, 0) + 0.3 * rgb(i, 1), 0.2 * rgb(i, 0) + 0.7 * rgb(i, 1), 0.9 * rgb(i, 2) + 0.1 * rgb(i, 1);
  }
  const ModelEvaluation ev = evaluate_model("matrix-3x3", rgb, xyz, {});
  return profile_to_json(make_profile(ev, {}, {}, rgb, xyz));
}

/// The profile with `"ignored": [0, 0, ...]` (n zeros) as its first member.
std::string profile_with_array(std::size_t n) {
  const std::string p = small_profile_json();
  std::string big = "{\"ignored\": [";
  big.reserve(n * 2 + p.size() + 32);
  for (std::size_t i = 0; i < n; ++i) big += i ? ",0" : "0";
  big += "],";
  big += p.substr(p.find('{') + 1);
  return big;
}

}  // namespace

TEST_CASE("limits: a 1,000,000-row patch table is refused at once (fit and evaluate read it so)", "[limits][io]") {
  const std::string rgb = patch_rows(1000000, "patch,R,G,B\n");
  expect_limit("1,000,000-row CSV, " + std::to_string(rgb.size() >> 20) + " MB", [&] { read_patch_file(rgb, "rgb.csv"); });
  // Under the byte limit but over the row limit: refused by the row count, before any line is kept.
  const std::string rows = patch_rows(limits::kMaxTableRows + 1, "patch,R,G,B\n");
  REQUIRE(rows.size() < limits::kMaxTextFileBytes);
  expect_limit(std::to_string(limits::kMaxTableRows + 1) + "-row CSV", [&] { read_patch_file(rows, "rgb.csv"); });
  std::string cgats = "CGATS.17\nBEGIN_DATA_FORMAT\nSAMPLE_ID RGB_R RGB_G RGB_B\nEND_DATA_FORMAT\nBEGIN_DATA\n";
  for (std::size_t i = 0; i <= limits::kMaxTableRows; ++i) cgats += "P" + std::to_string(i) + " 1 2 3\n";
  cgats += "END_DATA\n";
  expect_limit("CGATS with too many rows", [&] { read_patch_file(cgats, "rgb.ti3"); });
  // At the limit it still reads.
  CHECK(read_patch_file(patch_rows(1000, "patch,R,G,B\n"), "rgb.csv").ids.size() == 1000);
}

TEST_CASE("limits: columns of a table", "[limits][io]") {
  std::string header = "wavelength";
  for (std::size_t k = 0; k <= limits::kMaxTableColumns; ++k) header += ",s" + std::to_string(k);
  expect_limit("CSV with too many columns", [&] { read_patch_file(header + "\n", "s.csv"); });
}

/// The parser says LIMIT_EXCEEDED and profile_from_json keeps that code (other JSON errors are
/// PROFILE_INVALID); the message names the limit.
void expect_profile_limit(const std::string& what, const std::string& text) {
  expect_limit(what + " (json::parse)", [&] { json::parse(text); });
  const auto t0 = std::chrono::steady_clock::now();
  try {
    profile_from_json(text);
    FAIL("no error");
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(e.code() == ErrorCode::LimitExceeded);
    CHECK(std::string(e.what()).find("the limit") != std::string::npos);
    std::printf("limits: %s -> profile_from_json %s in %.3f s\n", what.c_str(), e.code_name(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
}

TEST_CASE("limits: profiles — 32 MB with a huge ignored array, 87 MB, and the JSON limits", "[limits][json]") {
  expect_profile_limit("32 MB profile, an ignored array of 16 M elements", profile_with_array(16u << 20));
  expect_profile_limit("87 MB profile", profile_with_array(87u << 19));
  // Within the byte limit, an ignored array past the element limit is refused while parsing,
  // so it is never stored.
  const std::string p_arr = profile_with_array(limits::kMaxJsonArray + 1);
  REQUIRE(p_arr.size() < limits::kMaxJsonBytes);
  expect_profile_limit("profile with an ignored array of kMaxJsonArray + 1 elements", p_arr);
  // Many small arrays: the total number of values is bounded too.
  std::string many = "[";
  for (std::size_t i = 0; i < limits::kMaxJsonValues / 4 + 1; ++i) many += i ? ",[0,0,0]" : "[0,0,0]";
  many += "]";
  REQUIRE(many.size() < limits::kMaxJsonBytes);
  expect_limit("JSON with kMaxJsonValues + values", [&] { json::parse(many); });
  expect_limit("JSON nested kMaxJsonDepth + 1 deep",
               [&] { json::parse(std::string(limits::kMaxJsonDepth + 1, '[') + std::string(limits::kMaxJsonDepth + 1, ']')); });
  CHECK_NOTHROW(json::parse(std::string(limits::kMaxJsonDepth, '[') + std::string(limits::kMaxJsonDepth, ']')));
  expect_limit("JSON string over kMaxJsonString", [&] { json::parse("\"" + std::string(limits::kMaxJsonString + 1, 'x') + "\""); });
  std::string members = "{";
  for (std::size_t i = 0; i <= limits::kMaxJsonArray; ++i) members += (i ? ",\"k" : "\"k") + std::to_string(i) + "\":0";
  members += "}";
  expect_limit("JSON object with kMaxJsonArray + 1 members", [&] { json::parse(members); });
}

TEST_CASE("limits: refitting leave-one-out above kMaxLeaveOneOutPatches is skipped with a message", "[limits][evaluation]") {
  const std::size_t n = limits::kMaxLeaveOneOutPatches + 1;
  PatchMatrix rgb(static_cast<Eigen::Index>(n), 3), xyz(static_cast<Eigen::Index>(n), 3);
  for (Eigen::Index i = 0; i < rgb.rows(); ++i) {
    rgb.row(i) << 1 + i % 97, 1 + i % 89, 1 + i % 83;
    xyz.row(i) << 0.5 * rgb(i, 0), 0.4 * rgb(i, 1) + 0.1 * rgb(i, 0), 0.3 * rgb(i, 2);
  }
  FitOptions psm;
  psm.objective = Objective::PatternSearch;
  expect_limit("pattern-search leave-one-out on " + std::to_string(n) + " patches", [&] { leave_one_out("matrix-3x3", rgb, xyz, psm); });
  // Least squares has a closed form: no limit.
  CHECK(leave_one_out("matrix-3x3", rgb, xyz).rows() == rgb.rows());
  const auto t0 = std::chrono::steady_clock::now();
  const ModelEvaluation ev = evaluate_model("matrix-3x3", rgb, xyz, psm);
  std::printf("limits: fit with leave-one-out on %zu patches: %.3f s, LOO skipped\n", n,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  CHECK_FALSE(ev.has_loo);
  CHECK(ev.fit.message.find("leave-one-out") != std::string::npos);
}

TEST_CASE("JSON type errors say 'an array', 'an object'", "[limits][json]") {
  const json::Value v = json::parse("{\"a\": 1}");
  try {
    v.at("a").as_array("coefficients");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "coefficients must be an array, got number");
  }
  require_code([&] { json::reject_unknown(json::parse("{\"a\":1,\"b\":2}"), {"a"}, "profile", ErrorCode::ProfileInvalid); },
               ErrorCode::ProfileInvalid);
  CHECK_NOTHROW(json::reject_unknown(json::parse("{\"a\":1}"), {"a", "c"}, "profile", ErrorCode::ProfileInvalid));
}

TEST_CASE("JSON counts: as_int takes whole numbers in range and refuses the rest (fuzz_profile's 7e9 patches)", "[limits][json]") {
  const json::Value v = json::parse(R"({"n": 24, "big": 7000000001, "neg": -1, "frac": 2.5, "s": "24"})");
  CHECK(v.at("n").as_int("n", 0, 100) == 24);
  for (const char* key : {"big", "neg", "frac", "s"})
    require_code([&] { v.at(key).as_int(key, 0, limits::kMaxJsonInt); }, ErrorCode::ProfileInvalid);
  try {
    v.at("big").as_int("training.patches", 0, 100);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "training.patches must be a whole number from 0 to 100, got 7000000001");
  }

  // The profile the long fuzz run found has "patches": 07000000001 (tests/fuzz/corpus/profile/
  // crash-6c3b46f4…; the parser now refuses the leading zero too): every count a profile stores is
  // read through as_int.
  std::string text = test::read_test_file("tests/fuzz/corpus/profile/root2.json");
  const std::string from = "\"patches\": 24";
  REQUIRE(text.find(from) != std::string::npos);
  CHECK(profile_from_json(text).training_patches == 24);
  text.replace(text.find(from), from.size(), "\"patches\": 7000000001");
  require_code([&] { profile_from_json(text); }, ErrorCode::ProfileInvalid);
}

TEST_CASE("JSON numbers follow RFC 8259 and stay finite, like the page's JSON.parse", "[limits][json]") {
  for (const char* good : {"0", "-0", "24", "-1.5", "1e5", "1E+5", "2.5e-3", "0.000001", "1.7976931348623157e308"})
    CHECK_NOTHROW(json::parse(good));
  CHECK(json::parse("2.5e-3").as_number() == 2.5e-3);
  for (const char* bad : {"07000000001", "01", "1.", ".5", "-", "1e", "1e+", "1.2.3", "1e5e5", "--1", "+1", "1e400", "-1e400"})
    require_code([&] { json::parse(bad); }, ErrorCode::ParseError);
}

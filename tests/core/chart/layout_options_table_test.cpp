// The custom grid's and the sampling's option rows (layout_option_table, the page's inputs) against
// the checks chart_layout() and sample_chart() make: every value inside a row's bounds, in any
// combination, is accepted; past a bound the engine checks, it is refused.
#include <map>
#include <string>

#include "option_rows.hpp"
#include "test_support.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/error.hpp"

using tristim::test::code_of;
using namespace tristim;

namespace {

std::map<std::string, OptionSpec> by_name() {
  std::map<std::string, OptionSpec> m;
  for (const OptionSpec& o : layout_option_table()) m[o.name] = o;
  return m;
}

/// A custom layout with every option at its default, then `set` (name -> value) applied.
LayoutOptions custom(const std::map<std::string, double>& set) {
  LayoutOptions lo;
  lo.chart = "custom";
  std::map<std::string, double> v;
  for (const OptionSpec& o : layout_option_table()) v[o.name] = o.default_number;
  for (const auto& [k, x] : set) v.at(k) = x;
  lo.rows = static_cast<int>(v["rows"]);
  lo.columns = static_cast<int>(v["columns"]);
  lo.gap = v["gap"];
  lo.margin_left = v["margin_left"];
  lo.margin_top = v["margin_top"];
  lo.margin_right = v["margin_right"];
  lo.margin_bottom = v["margin_bottom"];
  return lo;
}

RawImage grey(int w, int h) {
  RawImage img;
  img.width = w;
  img.height = h;
  img.meta.saturation = {16000, 16000, 16000};
  img.rgb.assign(size_t(w) * h * 3, 1000.f);
  img.saturated.assign(size_t(w) * h, 0);
  return img;
}

}  // namespace

TEST_CASE("layout option table: its rows, units and steps", "[chart][catalog]") {
  CHECK(tristim::test::check_number_rows(layout_option_table(), false) ==
        "rows columns gap margin_left margin_top margin_right margin_bottom area ");
  CHECK(by_name().at("area").default_number == SampleOptions{}.area);
  CHECK(by_name().at("margin_top").unit == "fraction of the chart's height");
}

TEST_CASE("layout option table: chart_layout takes every value in the bounds and refuses past them", "[chart][catalog]") {
  const auto spec = by_name();
  const auto& R = spec.at("rows");
  const auto& C = spec.at("columns");
  const auto& G = spec.at("gap");
  // Each bound alone, and every margin at its max at once (opposite margins together).
  for (double r : {R.min, R.max}) CHECK(chart_layout(custom({{"rows", r}, {"columns", C.min}})).patches.size() == size_t(r));
  for (double c : {C.min, C.max}) CHECK(chart_layout(custom({{"rows", R.min}, {"columns", c}})).patches.size() == size_t(c));
  for (double g : {G.min, G.max}) CHECK(chart_layout(custom({{"gap", g}})).gap == g);
  std::map<std::string, double> margins;
  for (const char* m : {"margin_left", "margin_top", "margin_right", "margin_bottom"}) margins[m] = spec.at(m).max;
  const ChartLayout L = chart_layout(custom(margins));
  CHECK(L.patches.front().u0 == spec.at("margin_left").max);
  CHECK(L.patches.back().v1 == Approx(1 - spec.at("margin_bottom").max));
  // Past a bound: refused with InvalidArgument.
  CHECK(code_of([&] { chart_layout(custom({{"rows", R.min - 1}})); }) == ErrorCode::InvalidArgument);
  CHECK(code_of([&] { chart_layout(custom({{"rows", R.max + 1}})); }) == ErrorCode::InvalidArgument);
  CHECK(code_of([&] { chart_layout(custom({{"columns", C.min - 1}})); }) == ErrorCode::InvalidArgument);
  CHECK(code_of([&] { chart_layout(custom({{"columns", C.max + 1}})); }) == ErrorCode::InvalidArgument);
  CHECK(code_of([&] { chart_layout(custom({{"gap", G.max + G.step}})); }) == ErrorCode::InvalidArgument);
  CHECK(code_of([&] { chart_layout(custom({{"margin_left", -spec.at("margin_left").step}})); }) == ErrorCode::InvalidArgument);
}

TEST_CASE("layout option table: sample_chart takes the sampled area's bounds and refuses past them", "[chart][catalog]") {
  const auto spec = by_name();  // kept: a reference into by_name()'s temporary map would dangle
  const auto& A = spec.at("area");
  const RawImage img = grey(1200, 600);  // patches of ~170 x 120 px: the smallest area still has pixels
  const std::array<double, 8> corners = {10, 10, 1190, 10, 1190, 590, 10, 590};
  SampleOptions so;
  for (double a : {A.min, A.max}) {
    so.area = a;
    CHECK(sample_chart(img, LayoutOptions{}, corners, so).patches.size() == 24);
  }
  so.area = A.max + A.step;
  CHECK(code_of([&] { sample_chart(img, LayoutOptions{}, corners, so); }) == ErrorCode::InvalidArgument);
}

// A light trap's box rows (light_trap_option_table: the page's boxes) against measure_light_trap:
// a box inside its rows that ends at the image's right or bottom edge is measured; one pixel past
// an edge is refused with CORNERS_OUTSIDE naming the light trap (Abed 2013 App. C step 1).
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <string>

#include "synthetic.hpp"
#include "test_support.hpp"
#include "tristim/chart/light_trap.hpp"

using namespace tristim;

namespace {

// A W × H image of 500 DN with a dark cavity (20 DN) in its bottom-right corner, 30 × 40 pixels.
RawImage dark_corner(int W, int H) {
  RawImage img = test::blank_raw(W, H, 16000);
  std::fill(img.rgb.begin(), img.rgb.end(), 500.f);
  for (int y = H - 40; y < H; ++y)
    for (int x = W - 30; x < W; ++x)
      for (int c = 0; c < 3; ++c) img.rgb[(size_t(y) * W + x) * 3 + c] = 20.f;
  return img;
}

std::array<double, 8> box(double x, double y, double w, double h) { return {x, y, x + w, y, x + w, y + h, x, y + h}; }

/// "CODE: message" of measuring the trap at `corners`, or "" when it is measured.
std::string refusal(const RawImage& img, const std::array<double, 8>& corners) {
  try {
    measure_light_trap(img, corners);
  } catch (const Error& e) {
    return std::string(e.code_name()) + ": " + e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("light trap rows: the box's bounds are the image's, and measure_light_trap holds to them", "[capture][light_trap][catalog]") {
  const int W = 160, H = 100;
  std::map<std::string, OptionSpec> rows;
  std::string names;
  for (const OptionSpec& o : light_trap_option_table(W, H)) rows[o.name] = o, names += o.name + " ";
  CHECK(names == "x y width height ");
  for (const auto& [name, o] : rows) {
    INFO(name);
    CHECK(o.type == "integer");
    CHECK(o.step == 1);
    CHECK(o.unit == "px");
    CHECK(!o.label.empty());
    CHECK(!o.description.empty());
    CHECK(o.default_number >= o.min);
    CHECK(o.default_number <= o.max);
  }
  CHECK(rows.at("x").min == 0);
  CHECK(rows.at("x").max == W - 1);
  CHECK(rows.at("y").max == H - 1);
  CHECK(rows.at("width").min == 1);
  CHECK(rows.at("width").max == W);
  CHECK(rows.at("height").max == H);

  const RawImage img = dark_corner(W, H);
  // The cavity, its box ending at the right and bottom edges (x + width = W, y + height = H).
  const double x = W - 30, y = H - 40;
  CHECK(refusal(img, box(x, y, 30, 40)) == "");
  const LightTrap t = measure_light_trap(img, box(x, y, 30, 40));
  for (int c = 0; c < 3; ++c) CHECK(t.mean[c] == Approx(20).margin(1e-4));
  // The widest and tallest boxes the rows allow: the whole image.
  CHECK(refusal(dark_corner(W, H), box(rows.at("x").min, rows.at("y").min, rows.at("width").max, rows.at("height").max)) == "");
  // One pixel past an edge, on each side: refused, the trap named.
  for (const auto& past : {box(x + 1, y, 30, 40), box(x, y + 1, 30, 40), box(-1, y, 30, 40), box(x, -1, 30, 40)}) {
    const std::string why = refusal(img, past);
    INFO(why);
    CHECK(why.rfind("CORNERS_OUTSIDE: light trap: ", 0) == 0);
  }
  test::require_code([] { light_trap_option_table(0, 100); }, ErrorCode::InvalidArgument);
  test::require_code([] { light_trap_option_table(160, 0); }, ErrorCode::InvalidArgument);
}

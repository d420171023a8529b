// Chart layouts, homography and patch sampling: planted synthetic charts and the real Passport DNG.
#include <cmath>
#include <map>
#include <sstream>

#include "test_support.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/error.hpp"
#include "tristim/capture/raw.hpp"

using tristim::test::code_of;

using namespace tristim;

namespace {

// Corners of the Passport's classic side in the example DNG (half-resolution coordinates),
// found by eye on the preview: outer corners of A1, A6, D6, D1. Also in examples/web/passport.json.
const std::array<double, 8> kPassportCorners = {335, 291, 649, 285, 649, 486, 328, 488};


RawImage blank(int w, int h) {
  RawImage img;
  img.width = w;
  img.height = h;
  img.meta.make = "tristim";
  img.meta.model = "Synthetic";
  img.meta.saturation = {16000, 16000, 16000};
  img.rgb.assign(size_t(w) * h * 3, 0.f);
  img.saturated.assign(size_t(w) * h, 0);
  return img;
}

// Paints every patch of `layout` with a planted colour through the homography of `corners`
// (pixel centres mapped back to chart coordinates), gaps in a dark grey.
RawImage planted_chart(const LayoutOptions& lo, const std::array<double, 8>& corners, int w, int h,
                       std::map<std::string, std::array<double, 3>>& planted) {
  RawImage img = blank(w, h);
  const ChartLayout L = chart_layout(lo);
  const auto Hm = homography_unit_square(corners);
  // invert 3x3
  const double* m = Hm.data();
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
  const double inv[9] = {(m[4] * m[8] - m[5] * m[7]) / det, (m[2] * m[7] - m[1] * m[8]) / det, (m[1] * m[5] - m[2] * m[4]) / det,
                         (m[5] * m[6] - m[3] * m[8]) / det, (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
                         (m[3] * m[7] - m[4] * m[6]) / det, (m[1] * m[6] - m[0] * m[7]) / det, (m[0] * m[4] - m[1] * m[3]) / det};
  for (size_t k = 0; k < L.patches.size(); ++k)
    planted[L.patches[k].id] = {100.0 + 10 * k, 2000.0 + 7 * k, 5000.0 - 13 * k};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double X = x + 0.5, Y = y + 0.5;
      const double z = inv[6] * X + inv[7] * Y + inv[8];
      const double u = (inv[0] * X + inv[1] * Y + inv[2]) / z, v = (inv[3] * X + inv[4] * Y + inv[5]) / z;
      std::array<double, 3> col = {30, 30, 30};
      for (const auto& p : L.patches)
        if (u >= p.u0 && u < p.u1 && v >= p.v0 && v < p.v1) col = planted[p.id];
      for (int c = 0; c < 3; ++c) img.rgb[(size_t(y) * w + x) * 3 + c] = static_cast<float>(col[c]);
    }
  return img;
}

}  // namespace

TEST_CASE("patch ids follow the reference data conventions", "[chart]") {
  LayoutOptions o;
  o.chart = "cc24";
  ChartLayout L = chart_layout(o);
  REQUIRE(L.patches.size() == 24);
  CHECK(L.patches[0].id == "A1");
  CHECK(L.patches[5].id == "A6");
  CHECK(L.patches[6].id == "B1");
  CHECK(L.patches[23].id == "D6");
  o.chart = "passport";
  CHECK(chart_layout(o).patches[23].id == "D6");
  o.chart = "sg140";
  L = chart_layout(o);
  REQUIRE(L.patches.size() == 140);
  CHECK(L.rows == 10);
  CHECK(L.columns == 14);
  CHECK(L.patches[0].id == "A1");   // top-left
  CHECK(L.patches[1].id == "B1");   // letter = column
  CHECK(L.patches[13].id == "N1");  // top-right
  CHECK(L.patches[14].id == "A2");  // number = row
  CHECK(L.patches[139].id == "N10");
  o.chart = "custom";
  o.rows = 2;
  o.columns = 3;
  L = chart_layout(o);
  CHECK(L.patches.size() == 6);
  CHECK(L.patches[5].id == "R2C3");
  o.chart = "nope";
  CHECK(code_of([&] { chart_layout(o); }) == ErrorCode::UnknownId);
  o.chart = "custom";
  o.rows = 0;
  CHECK(code_of([&] { chart_layout(o); }) == ErrorCode::InvalidArgument);
}

TEST_CASE("homography maps the unit square onto the corners", "[chart]") {
  const std::array<double, 8> k = {12.5, 20, 300, 35, 280, 210, 5, 190};
  const auto H = homography_unit_square(k);
  const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    const double z = H[6] * uv[i][0] + H[7] * uv[i][1] + H[8];
    CHECK((H[0] * uv[i][0] + H[1] * uv[i][1] + H[2]) / z == Approx(k[2 * i]).margin(1e-9));
    CHECK((H[3] * uv[i][0] + H[4] * uv[i][1] + H[5]) / z == Approx(k[2 * i + 1]).margin(1e-9));
  }
}

TEST_CASE("sampling recovers planted patch values through a perspective homography", "[chart]") {
  for (const std::string chart : {"cc24", "sg140", "custom"}) {
    INFO(chart);
    LayoutOptions lo;
    lo.chart = chart;
    if (chart == "custom") {
      lo.rows = 3, lo.columns = 5, lo.gap = 0.2;
      lo.margin_left = lo.margin_right = 0.05;
      lo.margin_top = lo.margin_bottom = 0.1;
    }
    const std::array<double, 8> corners = {40.2, 30.7, 560.1, 52.3, 540.4, 380.9, 25.5, 350.2};
    std::map<std::string, std::array<double, 3>> planted;
    const RawImage img = planted_chart(lo, corners, 600, 420, planted);
    const ChartSample s = sample_chart(img, lo, corners);
    REQUIRE(s.patches.size() == planted.size());
    for (const auto& p : s.patches) {
      INFO(p.id);
      for (int c = 0; c < 3; ++c) {
        REQUIRE(p.mean[c] == Approx(planted[p.id][c]).epsilon(1e-9));
        REQUIRE(p.std[c] == Approx(0).margin(1e-6));
        REQUIRE(p.saturated_fraction[c] == 0);
      }
      REQUIRE(p.n >= 4);
      REQUIRE(p.flags.empty());
    }
  }
}

TEST_CASE("the sampled area shrinks with --area and patch flags are set", "[chart]") {
  LayoutOptions lo;
  const std::array<double, 8> corners = {10, 10, 310, 10, 310, 210, 10, 210};
  std::map<std::string, std::array<double, 3>> planted;
  RawImage img = planted_chart(lo, corners, 320, 220, planted);
  SampleOptions so;
  const int n50 = sample_chart(img, lo, corners, so).patches[0].n;
  so.area = 0.25;
  const int n25 = sample_chart(img, lo, corners, so).patches[0].n;
  CHECK(n25 < n50 / 3);
  // Saturate one pixel in the centre of A1 (green), make B1 dark, make C1 noisy.
  const ChartSample base = sample_chart(img, lo, corners);
  const auto cA1 = base.patches[0].centre, cB1 = base.patches[6].centre, cC1 = base.patches[12].centre,
             cD1 = base.patches[18].centre;
  img.saturated[size_t(cA1[1]) * img.width + size_t(cA1[0])] = 2;
  for (int y = -20; y <= 20; ++y)
    for (int x = -20; x <= 20; ++x) {
      const size_t iB = (size_t(cB1[1] + y) * img.width + size_t(cB1[0] + x)) * 3;
      for (int c = 0; c < 3; ++c) img.rgb[iB + c] = 5.f;
      const size_t iC = (size_t(cC1[1] + y) * img.width + size_t(cC1[0] + x)) * 3;
      for (int c = 0; c < 3; ++c) img.rgb[iC + c] = x < 0 ? 1000.f : 3000.f;  // a step: left dark, right bright
      const size_t iD = (size_t(cD1[1] + y) * img.width + size_t(cD1[0] + x)) * 3;  // flat but noisy
      for (int c = 0; c < 3; ++c) img.rgb[iD + c] = ((x + y) & 1) ? 1000.f : 3000.f;
    }
  const ChartSample s = sample_chart(img, lo, corners);
  CHECK(s.patches[0].flags == std::vector<std::string>{"saturated"});
  CHECK(s.patches[0].saturated_fraction[1] == Approx(1.0 / s.patches[0].n));
  CHECK(s.patches[0].saturated_fraction[0] == 0);
  CHECK(s.patches[6].flags == std::vector<std::string>{"dark"});
  CHECK(s.patches[12].flags == std::vector<std::string>{"nonuniform"});
  // Pixel noise with σ/mean = 50 % on a flat patch is noise, not structure: no flag.
  CHECK(s.patches[18].std[1] / s.patches[18].mean[1] > 0.4);
  CHECK(s.patches[18].flags.empty());
  const std::string csv = chart_sample_to_csv(s);
  CHECK(csv.rfind("patch,R,G,B,R_std,G_std,B_std,n,flags\nA1,", 0) == 0);
}

TEST_CASE("bad corners and tiny patches give coded errors", "[chart][bad]") {
  const RawImage img = blank(200, 100);
  LayoutOptions lo;
  const std::array<double, 8> good = {10, 10, 190, 10, 190, 90, 10, 90};
  CHECK_NOTHROW(sample_chart(img, lo, good));
  CHECK(code_of([&] { sample_chart(img, lo, {10, 10, 250, 10, 190, 90, 10, 90}); }) == ErrorCode::CornersOutside);
  CHECK(code_of([&] { sample_chart(img, lo, {-1, 10, 190, 10, 190, 90, 10, 90}); }) == ErrorCode::CornersOutside);
  CHECK(code_of([&] { sample_chart(img, lo, {10, 10, 190, 10, 10, 90, 190, 90}); }) == ErrorCode::CornersCrossed);
  CHECK(code_of([&] { sample_chart(img, lo, {10, 10, 10, 90, 190, 90, 190, 10}); }) == ErrorCode::CornersCrossed);  // mirrored
  CHECK(code_of([&] { sample_chart(img, lo, {10, 10, 100, 10, 190, 10, 100, 10}); }) == ErrorCode::CornersCrossed);  // collinear
  CHECK(code_of([&] { sample_chart(img, lo, {10, 10, 22, 10, 22, 18, 10, 18}); }) == ErrorCode::PatchTooSmall);
  SampleOptions so;
  so.area = 0;
  CHECK(code_of([&] { sample_chart(img, lo, good, so); }) == ErrorCode::InvalidArgument);
}

TEST_CASE("Passport DNG: sampled patches match dcraw_emu's derived table up to one scale", "[chart][real]") {
  const std::string raw = test::read_test_file(test::passport_dng);
  const RawImage img = decode_raw(std::vector<std::uint8_t>(raw.begin(), raw.end()));
  LayoutOptions lo;
  lo.chart = "passport";
  const ChartSample s = sample_chart(img, lo, kPassportCorners);
  REQUIRE(s.patches.size() == 24);
  // The derived table: 11x11-pixel means of dcraw_emu -4 -o 0 -r 1 1 1 1 -h, scaled to 16 bit
  // by LibRaw (its scale, not ours) and clipped at 0: compare after one global scale factor.
  std::istringstream in(test::read_test_file(test::passport_rgb_csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::array<double, 6>> ref;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    REQUIRE(cells.size() == 8);
    ref.push_back({std::stod(cells[2]), std::stod(cells[3]), std::stod(cells[4]), std::stod(cells[5]),
                   std::stod(cells[6]), std::stod(cells[7])});
  }
  REQUIRE(ref.size() == 24);
  std::vector<double> ratios;
  for (int k = 0; k < 24; ++k)
    for (int c = 0; c < 3; ++c) ratios.push_back(ref[k][c] / s.patches[k].mean[c]);
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  const double scale = ratios[ratios.size() / 2];
  // Tolerance: 2 % plus 4 standard errors of the 11x11 reference window (its pixel noise).
  double worst = 0;
  std::string worst_at;
  for (int k = 0; k < 24; ++k)
    for (int c = 0; c < 3; ++c) {
      const double ours = s.patches[k].mean[c] * scale, theirs = ref[k][c];
      const double tol = 0.02 * theirs + 4 * ref[k][c + 3] / 11.0;
      const double excess = std::abs(ours - theirs) / tol;
      if (excess > worst) {
        worst = excess;
        std::ostringstream ss;
        ss << s.patches[k].id << " channel " << "RGB"[c] << ": ours*scale " << ours << " vs " << theirs << " (tol " << tol << ")";
        worst_at = ss.str();
      }
    }
  INFO("scale " << scale << "; worst " << worst_at);
  CHECK(worst <= 1.0);
  // The white patch D1 is brighter than every other neutral, and nothing is clipped.
  for (int k = 19; k < 24; ++k) CHECK(s.patches[18].mean[1] > s.patches[k].mean[1]);
  for (const auto& p : s.patches) CHECK(p.saturated_fraction[1] == 0);
}

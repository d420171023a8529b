// The lab's charts of one's own: Munsell selections and uploaded reflectances drawn as a generated
// grid (the custom layout), rendered to a DNG and sampled back at the truth's corners.
#include <cmath>
#include <sstream>
#include <string>

#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/json.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

// Worst |sampled − truth| over the patches (rows of `sampled` in the custom layout's order, the
// truth's patches in the same cells), with where it is.
double worst_error(const std::vector<std::pair<std::string, std::array<double, 3>>>& sampled, const LabRender& r,
                   std::string& where) {
  double worst = 0;
  for (size_t i = 0; i < r.patches.size(); ++i) {
    REQUIRE(sampled[i].first == r.patches[i].cell);
    for (size_t c = 0; c < 3; ++c) {
      const double e = std::abs(sampled[i].second[c] - r.patches[i].rgb[c]);
      if (e > worst) {
        worst = e;
        where = r.patches[i].id + " (" + r.patches[i].cell + ") channel " + std::to_string(c) + ": sampled " +
                std::to_string(sampled[i].second[c]) + ", truth " + std::to_string(r.patches[i].rgb[c]);
      }
    }
  }
  return worst;
}

std::vector<std::pair<std::string, std::array<double, 3>>> means(const ChartSample& s) {
  std::vector<std::pair<std::string, std::array<double, 3>>> out;
  for (const auto& p : s.patches) out.emplace_back(p.id, p.mean);
  return out;
}

}  // namespace

TEST_CASE("lab render: grid shape for N patches is a 3:2 chart that holds them", "[lab]") {
  CHECK(lab_grid_shape(24) == std::array<int, 2>{4, 6});
  CHECK(lab_grid_shape(3) == std::array<int, 2>{1, 3});
  CHECK(lab_grid_shape(140) == std::array<int, 2>{10, 15});
  for (int n = 1; n <= 300; ++n) {
    const auto s = lab_grid_shape(n);
    INFO(n);
    CHECK(s[0] * s[1] >= n);
    CHECK((s[0] - 1) * s[1] < n);  // no empty row
  }
  test::require_code([] { lab_grid_shape(0); }, ErrorCode::InvalidArgument);
}

TEST_CASE("lab render: a Munsell selection, rendered noise-off at tilted corners, is sampled back to 1e-6", "[lab]") {
  LabRenderOptions o;
  o.camera = "Nikon_D850";
  o.chart = "munsell:5R4/14,10YR6/10,5PB";  // two chips and the 5PB hue page
  o.illuminant = "D50";
  o.exposure = 0.7;
  o.flare = 0.01;
  o.corners = {150, 110, 720, 80, 750, 500, 130, 530};
  const LabRender r = render_lab_chart(o);
  const SpectralData sel = lab_munsell_selection(o.chart);
  REQUIRE(sel.names.size() > 20);
  CHECK(sel.names[0] == "5R4/14");
  CHECK(sel.names[1] == "10YR6/10");
  for (size_t i = 2; i < sel.names.size(); ++i) CHECK(sel.names[i].compare(0, 3, "5PB") == 0);
  const auto shape = lab_grid_shape(static_cast<int>(sel.names.size()));
  CHECK(r.layout == "custom");
  CHECK(r.rows == shape[0]);
  CHECK(r.columns == shape[1]);
  REQUIRE(r.patches.size() == static_cast<size_t>(r.rows * r.columns));  // every cell, empty ones as board
  // Planted: each patch's linear value = exposure × saturation × the virtual camera's response to
  // the chip (white diffuser's G = 1) + the flare, computed here from the Munsell set directly.
  const auto rgb = simulate_camera_RGB(camera_ssf(o.camera), sel, illuminant_spd("D50"));
  for (size_t i = 0; i < sel.names.size(); ++i) {
    CHECK(!r.patches[i].board);
    CHECK(r.patches[i].id == sel.names[i]);
    for (int c = 0; c < 3; ++c)
      CHECK(r.patches[i].linear[static_cast<size_t>(c)] ==
            Approx(0.7 * r.saturation * rgb[i][c] + 0.01 * r.white[static_cast<size_t>(c)]).epsilon(1e-12));
  }
  // The DNG, decoded, sampled with the custom layout at the truth's corners.
  const RawImage img = decode_raw(lab_render_dng(r));
  LayoutOptions lo;
  lo.chart = "custom";
  lo.rows = r.rows;
  lo.columns = r.columns;
  const ChartSample s = sample_chart(img, lo, r.corners);
  REQUIRE(s.patches.size() == static_cast<size_t>(r.rows * r.columns));
  std::string where;
  const double worst = worst_error(means(s), r, where);
  INFO("worst " << where << " (tolerance 1e-6)");
  CHECK(worst <= 1e-6);
  // Cells past the last chip show the board (ρ = 0.03 of the white, plus the flare).
  for (size_t k = sel.names.size(); k < s.patches.size(); ++k) {
    CHECK(r.patches[k].board);
    CHECK(s.patches[k].mean[1] == std::round(0.04 * r.white[1]));
  }
  // The truth names the layout and the sample options.
  const json::Value truth = lab_render_json(r);
  CHECK(truth.at("layout").at("rows").as_number() == r.rows);
  CHECK(truth.at("sample_args").as_string().find("--chart custom --rows " + std::to_string(r.rows)) == 0);
  CHECK(truth.at("patches").as_array()[0].at("cell").as_string() == "R1C1");
}

TEST_CASE("lab render: 7 chips in a 2 x 4 grid: the empty cell R2C4 is a board patch of the truth and samples back", "[lab]") {
  LabRenderOptions o;
  o.camera = "Nikon_D850";
  o.chart = "munsell:5R4/14,10YR6/10,5Y8/10,5G5/8,5B5/6,5PB4/10,5P4/10";
  o.illuminant = "D50";
  o.flare = 0.01;  // default exposure
  const LabRender r = render_lab_chart(o);
  REQUIRE(r.rows == 2);
  REQUIRE(r.columns == 4);
  REQUIRE(r.patches.size() == 8);
  for (size_t i = 0; i < 7; ++i) CHECK(!r.patches[i].board);
  const LabPatchTruth& b = r.patches[7];
  CHECK(b.board);
  CHECK(b.id == "R2C4");
  CHECK(b.cell == "R2C4");
  // Planted: the board is flat ρ = 0.03, so its camera response is 0.03 × the white's, plus flare.
  for (size_t c = 0; c < 3; ++c) CHECK(b.linear[c] == Approx((0.03 + 0.01) * r.white[c]).epsilon(1e-12));
  // Its XYZ, integrated here independently: D50 (tabulated, linear interpolation, held outside its
  // range) on the 1 nm CMF grid, X = 100 Σ ρ S x̄ / Σ S ȳ (CIE 15:2004 eqs 7.1-7.2).
  const SpectralData d50 = illuminant_spd("D50"), &cmf = cmfs(Observer::CIE1931_2);
  double sum[3] = {0, 0, 0}, norm = 0;
  for (size_t i = 0; i < cmf.wavelengths.size(); ++i) {
    const double l = cmf.wavelengths[i];
    const auto& w = d50.wavelengths;
    const auto& v = d50.values[0];
    double S = l <= w.front() ? v.front() : l >= w.back() ? v.back() : 0;
    for (size_t j = 0; j + 1 < w.size() && S == 0; ++j)
      if (l >= w[j] && l <= w[j + 1]) S = v[j] + (v[j + 1] - v[j]) * (l - w[j]) / (w[j + 1] - w[j]);
    for (size_t c = 0; c < 3; ++c) sum[c] += 0.03 * S * cmf.values[c][i];
    norm += S * cmf.values[1][i];
  }
  for (size_t c = 0; c < 3; ++c) CHECK(b.XYZ[c] == Approx(100 * sum[c] / norm).epsilon(1e-9));
  // Published check: 0.03 × the D50 white (ICC/ASTM E308: 96.42, 100, 82.52) to 0.1 %.
  for (int c = 0; c < 3; ++c) CHECK(b.XYZ[static_cast<size_t>(c)] == Approx(0.03 * whites::D50()[c]).epsilon(1e-3));
  // Sampled back with the custom layout: every cell, the board's included, to 1e-6.
  LayoutOptions lo;
  lo.chart = "custom";
  lo.rows = r.rows;
  lo.columns = r.columns;
  const ChartSample s = sample_chart(decode_raw(lab_render_dng(r)), lo, r.corners);
  REQUIRE(s.patches.size() == 8);
  std::string where;
  const double worst = worst_error(means(s), r, where);
  INFO("worst " << where << " (tolerance 1e-6)");
  CHECK(worst <= 1e-6);
  const json::Value truth = lab_render_json(r);
  const auto& patches = truth.at("patches").as_array();
  REQUIRE(patches.size() == 8);
  CHECK(patches[7].at("board").as_bool());
  CHECK(patches[6].find("board") == nullptr);
}

TEST_CASE("lab render: reflectances of one's own are drawn in their order, ids kept", "[lab]") {
  SpectralData mine = munsell_reflectances();  // any spectra: every 97th chip, renamed
  SpectralData set;
  set.wavelengths = mine.wavelengths;
  for (size_t k = 0; k < mine.names.size(); k += 97) {
    set.names.push_back("S" + std::to_string(k));
    set.values.push_back(mine.values[k]);
  }
  LabRenderOptions o;
  o.reflectances = set;
  o.chart = "my set";
  const LabRender r = render_lab_chart(o);
  REQUIRE(r.patches.size() == static_cast<size_t>(r.rows * r.columns));
  for (size_t i = 0; i < set.names.size(); ++i) CHECK(r.patches[i].id == set.names[i]);
  for (size_t i = set.names.size(); i < r.patches.size(); ++i) CHECK(r.patches[i].id == r.patches[i].cell);
  LayoutOptions lo;
  lo.chart = "custom";
  lo.rows = r.rows;
  lo.columns = r.columns;
  std::string where;
  CHECK(worst_error(means(sample_chart(decode_raw(lab_render_dng(r)), lo, r.corners)), r, where) <= 1e-6);
}

TEST_CASE("lab render: bad Munsell selections and sets of one's own give coded errors", "[lab]") {
  test::require_code([] { lab_munsell_selection("munsell:5R4/99"); }, ErrorCode::UnknownId);
  test::require_code([] { lab_munsell_selection("munsell:"); }, ErrorCode::InvalidArgument);
  test::require_code([] { lab_munsell_selection("munsell:banana"); }, ErrorCode::UnknownId);
  LabRenderOptions o;
  o.chart = "munsell:5R4/14,10YR6/10";  // two: too few for the DNG's colour matrix
  test::require_code([&] { render_lab_chart(o); }, ErrorCode::InvalidArgument);
  o.chart = "x";
  o.reflectances = lab_munsell_selection("5R4/14,10YR6/10,5R4/14,5PB4/10");  // repeats are dropped
  CHECK(o.reflectances.names.size() == 3);
  o.reflectances.names[2] = o.reflectances.names[0];
  test::require_code([&] { render_lab_chart(o); }, ErrorCode::InvalidArgument);
}

#ifndef __EMSCRIPTEN__
TEST_CASE("lab render --reflectances file.csv: tristim sample with the truth's sample_args recovers it to 1e-6", "[lab]") {
  test::ScratchDir dir("lab_grid");
  const std::string cli = TRISTIM_CLI;
  // A spectral CSV (id, then one column per wavelength), ids in the file's own spelling.
  std::ostringstream csv;
  csv << "id";
  for (int w = 380; w <= 780; w += 10) csv << ',' << w;
  csv << "\n";
  for (int i = 0; i < 10; ++i) {
    csv << "P0" << i;
    for (int w = 380; w <= 780; w += 10) csv << ',' << 0.1 + 0.4 * (1 + std::sin(w / 40.0 + i));
    csv << "\n";
  }
  test::spit(dir.d + "mine.csv", csv.str());
  const json::Value truth = json::parse(test::run_shell("'" + cli + "' lab render --camera Nikon_D850 --reflectances " + dir.d +
                                                        "mine.csv --illuminant A --out " + dir.d + "mine.dng"));
  const auto& patches = truth.at("patches").as_array();
  REQUIRE(patches.size() == 12);  // 10 spectra in a 3 × 4 grid: R3C3 and R3C4 are the board
  CHECK(patches[0].at("id").as_string() == "P00");
  CHECK(patches[9].at("id").as_string() == "P09");
  CHECK(patches[9].find("board") == nullptr);
  CHECK(patches[10].at("id").as_string() == "R3C3");
  CHECK(patches[11].at("board").as_bool());
  const std::string out = test::run_shell("'" + cli + "' sample " + dir.d + "mine.dng " + truth.at("sample_args").as_string());
  std::istringstream lines(out);
  std::string line;
  std::getline(lines, line);
  double worst = 0;
  for (const auto& p : patches) {
    REQUIRE(std::getline(lines, line));
    std::istringstream cells(line);
    std::string id, v;
    std::getline(cells, id, ',');
    CHECK(id == p.at("cell").as_string());
    const auto rgb = p.at("rgb").as_numbers();
    for (size_t c = 0; c < 3; ++c) {
      std::getline(cells, v, ',');
      worst = std::max(worst, std::abs(std::stod(v) - rgb[c]));
    }
  }
  CHECK(worst <= 1e-6);
  // --chart and --reflectances together are refused.
  const std::string both = test::run_shell("'" + cli + "' lab render --chart cc24 --reflectances " + dir.d +
                                           "mine.csv --out " + dir.d + "x.dng 2>&1", false);
  CHECK(both.find("INVALID_ARGUMENT") != std::string::npos);
}
#endif

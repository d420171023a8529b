// The lab's rendered chart photographs: a real DNG that LibRaw (and dcraw_emu) decode, from which
// detection and sampling recover the renderer's camera RGB exactly (noise off).
#include <cmath>
#include <cstdlib>
#include <string>

#include "refused.hpp"
#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/io/json.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

#ifndef __EMSCRIPTEN__
// `tristim sample` CSV -> (patch id, R, G, B) per row.
std::vector<std::pair<std::string, std::array<double, 3>>> sample_rows(const std::string& csv) {
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // header
  std::vector<std::pair<std::string, std::array<double, 3>>> out;
  while (std::getline(lines, line)) {
    std::istringstream cells(line);
    std::string id, v;
    std::getline(cells, id, ',');
    std::array<double, 3> rgb{};
    for (auto& x : rgb) {
      std::getline(cells, v, ',');
      x = std::stod(v);
    }
    out.emplace_back(id, rgb);
  }
  return out;
}
#endif

// Detects the chart in the decoded DNG and samples it at the detected corners; every patch's mean
// must equal the truth to 1e-6 DN (prints the worst).
void require_recovered(const LabRender& r) {
  const RawImage img = decode_raw(lab_render_dng(r));
  REQUIRE(img.width == r.width);
  REQUIRE(img.height == r.height);
  DetectOptions d;
  d.charts = {r.options.chart};
  const auto found = detect_charts(img, d);
  REQUIRE(!found.empty());
  REQUIRE(found[0].chart == r.options.chart);
  for (int i = 0; i < 8; ++i) CHECK(std::abs(found[0].corners[static_cast<size_t>(i)] - r.corners[static_cast<size_t>(i)]) < 0.5);
  LayoutOptions lo;
  lo.chart = r.options.chart;
  const ChartSample s = sample_chart(img, lo, found[0].corners);
  REQUIRE(s.patches.size() == r.patches.size());
  double worst = 0;
  std::string where;
  for (size_t i = 0; i < s.patches.size(); ++i) {
    REQUIRE(s.patches[i].id == r.patches[i].id);
    for (int c = 0; c < 3; ++c) {
      const double e = std::abs(s.patches[i].mean[static_cast<size_t>(c)] - r.patches[i].rgb[static_cast<size_t>(c)]);
      if (e > worst) {
        worst = e;
        where = s.patches[i].id + " channel " + std::to_string(c) + ": sampled " +
                std::to_string(s.patches[i].mean[static_cast<size_t>(c)]) + ", truth " +
                std::to_string(r.patches[i].rgb[static_cast<size_t>(c)]);
      }
    }
  }
  INFO("worst " << where << " (tolerance 1e-6)");
  CHECK(worst <= 1e-6);
}

}  // namespace

TEST_CASE("lab render: detection and sampling of the rendered DNG recover the camera RGB to 1e-6", "[lab]") {
  for (const char* chart : {"cc24", "passport", "sg140"}) {
    INFO("chart " << chart);
    LabRenderOptions o;
    o.camera = "Nikon_D850";
    o.chart = chart;
    o.illuminant = "D50";
    o.exposure = 0.7;
    o.flare = 0.01;
    require_recovered(render_lab_chart(o));
  }
  // Tilted corners and another CFA.
  LabRenderOptions o;
  o.camera = "Canon EOS 5D Mark II";
  o.cfa = "GBRG";
  o.corners = {160, 120, 700, 90, 730, 470, 140, 520};
  require_recovered(render_lab_chart(o));
}

TEST_CASE("lab render: the truth is the virtual camera's response scaled to the exposure", "[lab]") {
  LabRenderOptions o;
  o.camera = "Sony_ILCE-7M3";
  o.illuminant = "A";
  o.exposure = 0.4;
  const LabRender r = render_lab_chart(o);
  const SpectralData refl = chart_reflectances("cc24");
  const auto rgb = simulate_camera_RGB(camera_ssf(o.camera), refl, illuminant_spd("A"));
  REQUIRE(r.patches.size() == 24);
  // Planted: each patch's linear response = exposure × saturation × the camera's response (G of
  // the white diffuser = 1); the DN stored is its rounding. Patch order: A1..D6 in both.
  for (size_t i = 0; i < 24; ++i)
    for (int c = 0; c < 3; ++c) {
      CHECK(r.patches[i].linear[static_cast<size_t>(c)] == Approx(0.4 * r.saturation * rgb[i][c]).epsilon(1e-12));
      CHECK(std::abs(r.patches[i].rgb[static_cast<size_t>(c)] - r.patches[i].linear[static_cast<size_t>(c)]) <= 0.5);
    }
  CHECK(r.white[1] == Approx(0.4 * r.saturation).epsilon(1e-12));
  // The reference XYZ of the white patch D1 under A: Y near 90.
  CHECK(r.patches[18].XYZ[1] > 80);
  // DNG colour matrix: D65's white maps to a neutral whose largest value is 1.
  const Vec3 w = illuminant_white_XYZ(illuminant_spd("D65")) / 100.0;
  double mx = 0;
  for (int i = 0; i < 3; ++i) {
    const auto& m = r.dng.color_matrix;
    mx = std::max(mx, m[static_cast<size_t>(3 * i)] * w[0] + m[static_cast<size_t>(3 * i + 1)] * w[1] + m[static_cast<size_t>(3 * i + 2)] * w[2]);
  }
  CHECK(mx == Approx(1).epsilon(1e-9));
}

TEST_CASE("lab render: shot and read noise have the stated variance, fall-off the stated shape", "[lab]") {
  LabRenderOptions o;
  o.shot_gain = 2;
  o.read_noise = 5;
  o.seed = 3;
  const LabRender r = render_lab_chart(o);
  const RawImage img = decode_raw(lab_render_dng(r));
  LayoutOptions lo;
  lo.chart = "cc24";
  const ChartSample s = sample_chart(img, lo, r.corners);
  for (size_t i = 0; i < s.patches.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = r.patches[i].linear[static_cast<size_t>(c)];
      // A measurement pixel's G is the mean of two sensor pixels: half the variance.
      const double sigma = std::sqrt(2 * v + 25) / (c == 1 ? std::sqrt(2.0) : 1.0);
      const double n = s.patches[i].n;
      INFO(r.patches[i].id << " channel " << c);
      CHECK(std::abs(s.patches[i].mean[static_cast<size_t>(c)] - v) < 5 * sigma / std::sqrt(n) + 0.5);
      CHECK(s.patches[i].std[static_cast<size_t>(c)] == Approx(sigma).epsilon(0.1));
    }
  // Fall-off: 1 - a r² with r = 1 at the corners; a flat background pixel at the corner and the
  // centre of a patch at the image centre.
  LabRenderOptions f;
  f.falloff = 0.3;
  const LabRender rf = render_lab_chart(f);
  const RawImage fi = decode_raw(lab_render_dng(rf));
  const LabRender r0 = render_lab_chart(LabRenderOptions{});
  const RawImage f0 = decode_raw(lab_render_dng(r0));
  const double dx = 0.5 - f.width / 2.0, dy = 0.5 - f.height / 2.0;
  const double expected = 1 - 0.3 * (dx * dx + dy * dy) / (f.width * f.width / 4.0 + f.height * f.height / 4.0);
  CHECK(fi.at(0, 0, 1) / f0.at(0, 0, 1) == Approx(expected).epsilon(2e-3));
}

TEST_CASE("lab render: bad options give coded errors naming them", "[lab]") {
  const auto refused = [](ErrorCode code, auto set) { test::require_refused<LabRenderOptions>(code, set, render_lab_chart); };
  refused(ErrorCode::UnknownId, [](auto& o) { o.chart = "it8"; });
  refused(ErrorCode::UnknownId, [](auto& o) { o.camera = "Kodak Brownie"; });
  refused(ErrorCode::InvalidArgument, [](auto& o) { o.exposure = 0; });
  refused(ErrorCode::InvalidArgument, [](auto& o) { o.cfa = "RGGX"; });
  refused(ErrorCode::CornersOutside, [](auto& o) { o.corners = {10, 10, 2000, 10, 2000, 500, 10, 500}; });
}

#ifndef __EMSCRIPTEN__
TEST_CASE("lab render: the CLI's DNG opens in dcraw_emu and tristim detect + sample recover its truth", "[lab]") {
  const bool found = std::system("command -v dcraw_emu > /dev/null 2>&1") == 0;
  if (!found) FAIL("dcraw_emu is not installed (Debian package libraw-bin): run scripts/install-deps.sh");
  char tmpl[] = "/tmp/tristim-lab-XXXXXX";
  REQUIRE(mkdtemp(tmpl) != nullptr);
  const std::string d = std::string(tmpl) + "/", cli = TRISTIM_CLI;
  const json::Value truth = json::parse(test::run_shell(
      "'" + cli + "' lab render --camera 'Canon EOS 5D Mark II' --chart passport --illuminant D65 --out " + d + "chart.dng"));
  const auto corners = truth.at("corners").as_numbers();
  // tristim sample without --corners detects the chart first.
  const auto sampled = sample_rows(test::run_shell("'" + cli + "' sample " + d + "chart.dng --chart passport 2>/dev/null"));
  const auto& patches = truth.at("patches").as_array();
  REQUIRE(sampled.size() == patches.size());
  double worst = 0;
  for (size_t i = 0; i < patches.size(); ++i) {
    CHECK(sampled[i].first == patches[i].at("id").as_string());
    const auto rgb = patches[i].at("rgb").as_numbers();
    for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(sampled[i].second[c] - rgb[c]));
  }
  CHECK(worst <= 1e-6);
  // dcraw_emu: linear, no white balance, half size, 16-bit TIFF scaled by 65535 / saturation.
  test::run_shell("dcraw_emu -4 -o 0 -r 1 1 1 1 -h -T -Z " + d + "dcraw.tiff " + d + "chart.dng");
  const std::string dc = test::run_shell("'" + cli + "' sample " + d + "dcraw.tiff --chart passport --corners " +
                                         [&] {
                                           std::string s;
                                           for (double c : corners) s += (s.empty() ? "" : ",") + json::number_text(c);
                                           return s;
                                         }());
  const auto dcraw = sample_rows(dc);
  REQUIRE(dcraw.size() == patches.size());
  const double scale = 65535.0 / truth.at("saturation").as_number();
  double worst_dc = 0;
  for (size_t i = 0; i < patches.size(); ++i) {
    const auto rgb = patches[i].at("rgb").as_numbers();
    for (size_t c = 0; c < 3; ++c) worst_dc = std::max(worst_dc, std::abs(dcraw[i].second[c] / scale - rgb[c]));
  }
  INFO("dcraw_emu's patches vs the truth, worst DN (its 16-bit scaling rounds)");
  CHECK(worst_dc <= 1.0);
  std::system(("rm -rf '" + std::string(tmpl) + "'").c_str());
}
#endif

TEST_CASE("lab render: a TIFF through a gamma OECF holds the encoded truth, sampled back exactly", "[lab]") {
  LabRenderOptions o;
  o.camera = "Canon_EOS_5D_Mark_III";
  o.oecf = "gamma=2.2";
  o.flare = 0.02;
  const LabRender r = render_lab_chart(o);
  const auto bytes = lab_render_tiff(r);
  const RawImage img = decode_tiff(bytes.data(), bytes.size());
  REQUIRE(img.width == r.width);
  CHECK(img.meta.encoding == "stored");
  LayoutOptions lo;
  lo.chart = "cc24";
  const ChartSample s = sample_chart(img, lo, r.corners);
  const json::Value truth = lab_render_json(r, 65535);
  const auto& patches = truth.at("patches").as_array();
  for (size_t i = 0; i < s.patches.size(); ++i) {
    const auto stored = patches[i].at("stored").as_numbers();
    for (size_t c = 0; c < 3; ++c) {
      INFO(s.patches[i].id << " channel " << c);
      CHECK(s.patches[i].mean[c] == stored[c]);
      // Planted: stored = 65535 · (rgb / saturation)^(1/2.2), to the rounding.
      CHECK(std::abs(stored[c] - 65535 * std::pow(r.patches[i].rgb[c] / r.saturation, 1 / 2.2)) <= 0.5);
    }
  }
  o.oecf = "gamma=banana";
  test::require_code([&] { lab_render_files(o, "tiff"); }, ErrorCode::InvalidArgument);
  o.oecf = "gamma=2.2";
  test::require_code([&] { lab_render_files(o, "dng"); }, ErrorCode::InvalidArgument);
}

TEST_CASE("lab render: a JPEG through the sRGB OECF, detected and sampled, gives the stored 8-bit truth within 1.5 DN", "[lab]") {
  LabRenderOptions o;
  o.camera = "Nikon_D850";
  o.oecf = "sRGB";
  o.exposure = 0.7;
  const LabRenderFiles f = lab_render_files(o, "jpeg");
  REQUIRE(f.dng.size() > 2);
  CHECK(f.dng[0] == 0xFF);
  CHECK(f.dng[1] == 0xD8);
  const RawImage img = decode_jpeg(f.dng.data(), f.dng.size());
  const json::Value truth = json::parse(f.truth);
  CHECK(truth.at("jpeg_quality").as_number() == 95);
  CHECK(truth.at("full_scale").as_number() == 255);
  REQUIRE(img.width == static_cast<int>(truth.at("width").as_number()));
  DetectOptions d;
  d.charts = {"cc24"};
  const auto found = detect_charts(img, d);
  REQUIRE(!found.empty());
  LayoutOptions lo;
  lo.chart = "cc24";
  const ChartSample s = sample_chart(img, lo, found[0].corners);
  const auto& patches = truth.at("patches").as_array();
  REQUIRE(s.patches.size() == patches.size());
  const LabRender r = render_lab_chart(o);
  double worst = 0;
  std::string where;
  for (size_t i = 0; i < s.patches.size(); ++i) {
    const auto stored = patches[i].at("stored").as_numbers();
    for (size_t c = 0; c < 3; ++c) {
      // Planted: stored = round(255 · sRGB(rgb / saturation)).
      CHECK(stored[c] == std::round(255 * sRGB_encode(r.patches[i].rgb[c] / r.saturation)));
      const double e = std::abs(s.patches[i].mean[c] - stored[c]);
      if (e > worst) {
        worst = e;
        where = s.patches[i].id + " channel " + std::to_string(c) + ": sampled " + std::to_string(s.patches[i].mean[c]) +
                ", stored " + std::to_string(stored[c]);
      }
    }
  }
  INFO("worst " << where << " (tolerance 1.5 DN: JPEG quality 95, 4:4:4, YCbCr rounding)");
  CHECK(worst <= 1.5);
  o.jpeg_quality = 0;
  test::require_code([&] { lab_render_files(o, "jpeg"); }, ErrorCode::InvalidArgument);
  test::require_code([&] { lab_render_files(o, "png"); }, ErrorCode::InvalidArgument);
}

TEST_CASE("lab render: every OECF the page offers is one lab_encode knows, 0 and saturation map to 0 and 1", "[lab]") {
  LabRenderOptions o;
  for (const auto& id : lab_oecf_ids()) {
    INFO(id);
    o.oecf = id;
    CHECK(lab_encode(o, 0, 1000) == 0);
    CHECK(std::abs(lab_encode(o, 1000, 1000) - 1) < 1e-15);
  }
}

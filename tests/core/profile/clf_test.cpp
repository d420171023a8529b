// Common LUT Format (profile/clf.hpp): the writer and strict reader round trip, OpenColorIO loads
// tristim's IDT without a warning and gives tristim's own values to 1e-5 (ociochecklut, native
// only: a program installed by scripts/install-deps.sh), and the reader's coded refusals.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "test_support.hpp"
#include "text_edit.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/clf.hpp"
#include "tristim/profile/idt.hpp"
#include "tristim/simulate/virtual_camera.hpp"
#ifndef __EMSCRIPTEN__
#include <unistd.h>

#include "shell.hpp"
#endif

using namespace tristim;

namespace {

ClfDocument example_clf(bool with_lut) {
  ClfDocument c;
  c.id = "t<1>";
  c.name = "a & \"b\"";
  c.description = "camera 'x'";
  c.input_descriptor = "in";
  c.output_descriptor = "ACES2065-1";
  c.info = {{"Camera", "Canon <EOS> & co"}, {"Illuminant", "D55"}};
  c.matrix << 1.5, -0.25, 0.125, 0.0625, 1.1, -0.2, 0.01, -0.3, 1.4;
  if (with_lut)
    for (int i = 0; i < 17; ++i) {
      const double x = i / 16.0;
      c.lut1d.emplace_back(std::pow(x, 2.2), std::pow(x, 2.0), std::pow(x, 1.8));
    }
  return c;
}

}  // namespace

TEST_CASE("clf: write and read back", "[clf]") {
  for (bool lut : {false, true}) {
    const ClfDocument c = example_clf(lut);
    const std::string xml = write_clf(c);
    const ClfDocument b = read_clf(xml);
    CHECK(b.id == c.id);
    CHECK(b.name == c.name);
    CHECK(b.description == c.description);
    CHECK(b.info == c.info);
    CHECK(b.lut1d.size() == c.lut1d.size());
    CHECK((b.matrix - c.matrix).cwiseAbs().maxCoeff() < 1e-12);
    for (std::size_t i = 0; i < c.lut1d.size(); ++i) CHECK((b.lut1d[i] - c.lut1d[i]).cwiseAbs().maxCoeff() < 1e-9);
    CHECK(write_clf(b) == xml);  // what is read writes the same bytes
  }
  // The LUT1D interpolates linearly between its entries, then the matrix applies.
  const ClfDocument c = example_clf(true);
  const Vec3 mid = apply_clf(c, Vec3(0.5, 0.5, 0.5));
  CHECK((mid - c.matrix * Vec3(std::pow(0.5, 2.2), 0.25, std::pow(0.5, 1.8))).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("clf: the IDT's CLF carries the recipe and maps the camera white to ACES 1,1,1", "[clf]") {
  const IdtResult r = idt_from_sensitivities(camera_ssf("Nikon_D850"), illuminant_spd("D55"), idt_training_190());
  const IdtRecipe recipe = {{"Camera", "Nikon_D850"}, {"Illuminant", "D55"}, {"Training", "190 (rawtoaces v1)"}};
  const ClfDocument c = read_clf(write_clf(idt_clf(r, recipe)));
  CHECK((c.matrix - r.camera_matrix()).cwiseAbs().maxCoeff() < 1e-9);
  const Vec3 white = apply_clf(c, r.white_balance.cwiseInverse());
  CHECK((white - Vec3::Ones()).cwiseAbs().maxCoeff() < 1e-9);
  bool camera = false;
  for (const auto& kv : c.info) camera = camera || (kv.first == "Camera" && kv.second == "Nikon_D850");
  CHECK(camera);
  const json::Value j = idt_json(r, recipe);
  CHECK(j.at("white_balance").as_numbers("white_balance")[1] == 1.0);
  CHECK(j.at("matrix").as_array().size() == 3);
}

TEST_CASE("clf: the reader refuses broken files with coded errors", "[clf]") {
  const std::string good = write_clf(example_clf(true));
  auto replaced = [&](const std::string& from, const std::string& to) { return test::replaced(good, from, to); };
  test::require_code([&] { read_clf(""); }, ErrorCode::ParseError);
  test::require_code([&] { read_clf(good.substr(0, good.size() / 2)); }, ErrorCode::ParseError);
  test::require_code([&] { read_clf(replaced("</Matrix>", "</Matrx>")); }, ErrorCode::ParseError);
  test::require_code([&] { read_clf(replaced("<ProcessList", "<ProcessLost")); }, ErrorCode::ParseError);
  test::require_code([&] { read_clf(replaced("dim=\"3 3\"", "dim=\"3 4\"")); }, ErrorCode::ParseError);
  test::require_code([&] { read_clf(replaced("1.5 -0.25", "1.5x -0.25")); }, ErrorCode::NonNumeric);
  test::require_code([&] { read_clf(replaced("1.5 -0.25", "nan -0.25")); }, ErrorCode::NonFinite);
  test::require_code([&] { read_clf(replaced("1.5 -0.25", "-0.25")); }, ErrorCode::RowLength);
  test::require_code([&] { read_clf(replaced("dim=\"17 3\"", "dim=\"99999 3\"")); }, ErrorCode::LimitExceeded);
  test::require_code([&] { read_clf(replaced("&amp;", "&bogus;")); }, ErrorCode::ParseError);
  test::require_code([&] { read_clf(replaced("<Matrix id", "<Range/><Matrix id")); }, ErrorCode::ParseError);
  std::string no_matrix = good.substr(0, good.find("  <Matrix")) + "</ProcessList>\n";
  test::require_code([&] { read_clf(no_matrix); }, ErrorCode::ParseError);
  std::string deep = "<ProcessList>";
  for (int i = 0; i < 40; ++i) deep += "<Info>";
  test::require_code([&] { read_clf(deep); }, ErrorCode::ParseError);
  ClfDocument bad = example_clf(false);
  bad.info.emplace_back("not a name", "x");
  test::require_code([&] { write_clf(bad); }, ErrorCode::InvalidArgument);
}

#ifndef __EMSCRIPTEN__
TEST_CASE("clf: OpenColorIO (ociochecklut) loads the IDT without warnings and matches it to 1e-5", "[clf][readers]") {
  if (std::system("command -v ociochecklut > /dev/null 2>&1") != 0)
    FAIL("ociochecklut is not installed (Debian package opencolorio-tools): run scripts/install-deps.sh");
  char dir_template[] = "/tmp/tristim-clf-XXXXXX";
  REQUIRE(mkdtemp(dir_template) != nullptr);
  const std::string dir = dir_template;
  const IdtResult r = idt_from_sensitivities(camera_ssf("Canon EOS 5D Mark II"), illuminant_spd("D55"), idt_training_190());
  const ClfDocument idt = idt_clf(r, {{"Camera", "Canon EOS 5D Mark II"}, {"Illuminant", "D55"}});
  ClfDocument with_lut = example_clf(true);
  with_lut.matrix = idt.matrix;
  double worst = 0;
  for (const auto& [name, doc] : {std::pair<std::string, ClfDocument>{"idt", idt}, {"lut", with_lut}}) {
    const std::string path = dir + "/" + name + ".clf";
    test::spit(path, write_clf(doc));
    const std::string verbose = test::run_shell("ociochecklut -v " + path + " 2>&1");
    INFO(verbose);
    CHECK(verbose.find("arning") == std::string::npos);
    CHECK(verbose.find("rror") == std::string::npos);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 12; ++k) {
      const Vec3 rgb(u(rng), u(rng), u(rng));
      char args[128];
      std::snprintf(args, sizeof args, " %.9g %.9g %.9g", rgb[0], rgb[1], rgb[2]);
      const std::string outp = test::run_shell("ociochecklut " + path + args + " 2>&1");
      double v[3];
      REQUIRE(std::sscanf(outp.c_str(), "%lf %lf %lf", &v[0], &v[1], &v[2]) == 3);
      // tristim's own value: the IDT straight from the fit (B·diag(w)), through the LUT1D if any.
      const Vec3 want = name == "idt" ? Vec3(r.matrix * r.white_balance.cwiseProduct(rgb)) : apply_clf(doc, rgb);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(v[c] - want[c]));
    }
  }
  std::printf("OpenColorIO ociochecklut vs tristim's IDT (and LUT1D + matrix): worst |difference| %.2g (tolerance 1e-5)\n", worst);
  CHECK(worst < 1e-5);
  std::system(("rm -rf " + dir).c_str());
}
#endif

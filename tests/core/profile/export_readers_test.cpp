// Exports read back by the real readers people load them into (issue 15): lcms2's transicc,
// ArgyllCMS's xicclu/iccdump, OpenColorIO's ociochecklut/ocioconvert (ocioconvert reads the float
// TIFF writer's output through OpenImageIO). Native only: the readers are programs, installed by
// scripts/install-deps.sh (liblcms2-utils, argyll, opencolorio-tools); a missing one fails.
//
// The profile is the README's Passport example, made by the CLI itself: `tristim sample` on
// examples/web/passport.dng, `tristim reference --chart passport --illuminant D50`, `tristim fit
// --model Finlayson2015-2 --objective psm`, `tristim export`. Points: the 24 training patches and a
// 9³ grid of camera RGB spanning the training range per channel. Each check prints the worst point,
// the reader's and the model's values and the tolerance.
#ifndef __EMSCRIPTEN__
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "shell.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/profile.hpp"

using namespace tristim;

namespace {

using test::slurp;
using test::spit;

/// Runs a shell command; its stdout (stderr joins it when `merge`). Fails the test on a non-zero exit.
std::string run(const std::string& cmd, bool merge = false, bool must_succeed = true) {
  return test::run_shell(cmd + (merge ? " 2>&1" : " 2>/dev/null"), must_succeed);
}

void need_tool(const char* tool, const char* package) {
  const bool found = std::system(("command -v " + std::string(tool) + " > /dev/null 2>&1").c_str()) == 0;
  if (!found) FAIL(tool << " is not installed (Debian package " << package << "): run scripts/install-deps.sh");
}

/// The Passport example through the CLI, once per process.
struct Passport {
  // One folder per process (ctest runs the test cases in parallel), removed at exit.
  std::string dir = "tristim_readers_" + std::to_string(getpid());
  ~Passport() { std::system(("rm -rf " + dir).c_str()); }
  Profile lut, matrix;                 // Finlayson2015-2 psm; matrix-3x3 ls
  std::vector<std::string> labels;     // "A1".. then "grid(r,g,b)"
  PatchMatrix device;                  // 0..1, camera RGB / rgb_max of the LUT profile
  size_t n_patches = 0;
};

void build(Passport& p) {
  const std::string cli = TRISTIM_CLI;
  const std::string dng = std::string(TRISTIM_SOURCE_DIR) + "/examples/web/passport.dng";
  std::system(("mkdir -p " + p.dir).c_str());
  const std::string d = p.dir + "/";
  run(cli + " sample " + dng + " --chart passport --corners 335,291,649,285,649,486,328,488 > " + d + "patches.csv");
  run(cli + " reference --chart passport --illuminant D50 > " + d + "reference.csv");
  run(cli + " fit --rgb " + d + "patches.csv --xyz " + d + "reference.csv --model Finlayson2015-2 --objective psm --out " + d +
      "lut.json");
  run(cli + " fit --rgb " + d + "patches.csv --xyz " + d + "reference.csv --model matrix-3x3 --objective ls --out " + d +
      "matrix.json");
  for (const char* name : {"lut", "matrix"}) {
    const std::string j = d + name;
    run(cli + " export --profile " + j + ".json --icc " + j + "_v4.icc");
    run(cli + " export --profile " + j + ".json --icc " + j + "_v2.icc --icc-version 2.4");
    run(cli + " export --profile " + j + ".json --cube " + j + ".cube");
  }
  p.lut = profile_from_json(slurp(d + "lut.json"));
  p.matrix = profile_from_json(slurp(d + "matrix.json"));
  const PatchTable t = read_patch_file(slurp(d + "patches.csv"), "patches.csv");
  const double s = p.lut.rgb_max;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& v : t.RGB) {
    lo = lo.cwiseMin(v / s);
    hi = hi.cwiseMax(v / s);
  }
  const int L = 9;
  p.n_patches = t.RGB.size();
  p.device.resize(static_cast<Eigen::Index>(p.n_patches + L * L * L), 3);
  for (size_t i = 0; i < p.n_patches; ++i) {
    p.device.row(static_cast<Eigen::Index>(i)) = (t.RGB[i] / s).transpose();
    p.labels.push_back(t.ids[i]);
  }
  Eigen::Index row = static_cast<Eigen::Index>(p.n_patches);
  for (int b = 0; b < L; ++b)
    for (int g = 0; g < L; ++g)
      for (int r = 0; r < L; ++r, ++row) {
        const int k[3] = {r, g, b};
        for (int c = 0; c < 3; ++c) p.device(row, c) = lo[c] + (hi[c] - lo[c]) * k[c] / (L - 1.0);
        p.labels.push_back("grid(" + std::to_string(r) + "," + std::to_string(g) + "," + std::to_string(b) + ")");
      }
}

const Passport& passport() {
  static Passport P;
  static const bool ready = (build(P), true);
  (void)ready;
  return P;
}

/// The model's answer in a reader's frame: XYZ / white Y, Bradford-adapted to D50 for ICC (PCS).
PatchMatrix model_XYZ(const Profile& p, const PatchMatrix& device, bool pcs) {
  PatchMatrix out = predict(p.model, PatchMatrix(device * p.rgb_max)) / p.white[1];
  const Vec3 w = p.white / p.white[1], d50 = whites::D50() / 100.0;
  if (pcs && (w - d50).cwiseAbs().maxCoeff() > 1e-4) {
    const Mat3 cat = chromatic_adaptation_matrix(w, d50, ChromaticAdaptation::Bradford);
    for (Eigen::Index i = 0; i < out.rows(); ++i) out.row(i) = (cat * out.row(i).transpose()).transpose();
  }
  return out;
}

/// Compares a reader's XYZ with the model's (both white Y = 1) by CIEDE2000 under `white`, on the
/// training patches and on the grid separately; prints and checks the mean and the worst.
/// With `icc_range`, grid points whose model XYZ the ICC 16-bit PCSXYZ cannot hold (a component
/// below 0 or above 1 + 32767/32768: colours outside what the chart spans, e.g. strong red and blue
/// with no green, where the model predicts negative Y) are counted and left out.
void compare(const std::string& what, const PatchMatrix& got, const PatchMatrix& want, const Vec3& white, double mean_tol,
             double max_tol, bool icc_range = false) {
  const Passport& P = passport();
  REQUIRE(got.rows() == want.rows());
  const Vec3 w = white / white[1] * 100.0;
  for (int part = 0; part < 2; ++part) {
    const size_t from = part == 0 ? 0 : P.n_patches, to = part == 0 ? P.n_patches : static_cast<size_t>(got.rows());
    double sum = 0, worst = -1;
    size_t at = from, used = 0;
    for (size_t i = from; i < to; ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      if (icc_range && (want.row(r).minCoeff() < 0 || want.row(r).maxCoeff() > 1 + 32767.0 / 32768)) continue;
      ++used;
      const Vec3 a = got.row(static_cast<Eigen::Index>(i)).transpose() * 100.0;
      const Vec3 b = want.row(static_cast<Eigen::Index>(i)).transpose() * 100.0;
      const double de = delta_E_CIE2000(XYZ_to_Lab(a, w), XYZ_to_Lab(b, w));
      sum += de;
      if (de > worst) {
        worst = de;
        at = i;
      }
    }
    REQUIRE(used > 0);
    const double mean = sum / static_cast<double>(used);
    const auto e = static_cast<Eigen::Index>(at);
    char line[600];
    std::snprintf(line, sizeof line,
                  "%s, %s (%zu points%s): mean dE00 %.4f (tolerance < %.3g), max %.4f (tolerance < %.3g) at %s, "
                  "device %.5f %.5f %.5f: reader XYZ %.4f %.4f %.4f, model %.4f %.4f %.4f (Y = 100)",
                  what.c_str(), part == 0 ? "training patches" : "grid over the training range", used,
                  used < to - from ? (", " + std::to_string(to - from - used) + " outside the ICC XYZ range left out").c_str() : "", mean, mean_tol,
                  worst, max_tol, P.labels[at].c_str(), P.device(e, 0), P.device(e, 1), P.device(e, 2), 100 * got(e, 0),
                  100 * got(e, 1), 100 * got(e, 2), 100 * want(e, 0), 100 * want(e, 1), 100 * want(e, 2));
    std::printf("%s\n", line);
    INFO(line);
    CHECK(mean < mean_tol);
    CHECK(worst < max_tol);
  }
}

std::vector<std::array<double, 3>> numbers_after(const std::string& text, const std::string& marker, const char* format) {
  std::vector<std::array<double, 3>> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t at = marker.empty() ? 0 : line.rfind(marker);
    if (at == std::string::npos) continue;
    std::array<double, 3> v{};
    if (std::sscanf(line.c_str() + at, format, &v[0], &v[1], &v[2]) == 3) out.push_back(v);
  }
  return out;
}

PatchMatrix to_matrix(const std::vector<std::array<double, 3>>& v, double scale) {
  PatchMatrix m(static_cast<Eigen::Index>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) m(static_cast<Eigen::Index>(i), c) = v[i][c] * scale;
  return m;
}

/// lcms2: `transicc -t<intent> -i profile -o *XYZ`, device 0..255 in, "X=.. Y=.. Z=.." (Y = 100) out.
PatchMatrix transicc(const std::string& icc, const PatchMatrix& device, int intent) {
  const std::string in = icc + ".transicc.in";
  std::ostringstream s;
  s.precision(9);
  for (Eigen::Index i = 0; i < device.rows(); ++i) s << device(i, 0) * 255 << " " << device(i, 1) * 255 << " " << device(i, 2) * 255 << "\n";
  spit(in, s.str());
  const std::string out = run("transicc -t" + std::to_string(intent) + " -i " + icc + " -o '*XYZ' < " + in);
  const PatchMatrix m = to_matrix(numbers_after(out, "X=", "X=%lf Y=%lf Z=%lf"), 0.01);
  REQUIRE(m.rows() == device.rows());
  return m;
}

/// ArgyllCMS: `xicclu -ff -i<intent> -pX profile`, device 0..1 in, "-> X Y Z [XYZ]" (Y = 100) out.
PatchMatrix xicclu(const std::string& icc, const PatchMatrix& device, char intent) {
  const std::string in = icc + ".xicclu.in";
  std::ostringstream s;
  s.precision(9);
  for (Eigen::Index i = 0; i < device.rows(); ++i) s << device(i, 0) << " " << device(i, 1) << " " << device(i, 2) << "\n";
  spit(in, s.str());
  const std::string out = run(std::string("xicclu -ff -i") + intent + " -pX " + icc + " < " + in);
  const PatchMatrix m = to_matrix(numbers_after(out, "->", "-> %lf %lf %lf"), 0.01);
  REQUIRE(m.rows() == device.rows());
  return m;
}

/// The pixels of a little-endian, uncompressed, one-strip, 3 × 32-bit float TIFF (what
/// OpenImageIO writes for ocioconvert's output of a float TIFF input); fails the test otherwise.
std::vector<float> read_float_tiff(const std::string& b, int& width) {
  auto u16 = [&](size_t at) { return static_cast<uint32_t>(static_cast<uint8_t>(b.at(at)) | static_cast<uint8_t>(b.at(at + 1)) << 8); };
  auto u32 = [&](size_t at) { return u16(at) | u16(at + 2) << 16; };
  REQUIRE(b.compare(0, 4, std::string("II*\0", 4)) == 0);
  const size_t ifd = u32(4);
  uint32_t height = 0, compression = 0, offset = 0, count = 0, strips = 0, samples = 0;
  width = 0;
  for (uint32_t t = 0, n = u16(ifd); t < n; ++t) {
    const size_t e = ifd + 2 + 12 * t;
    const uint32_t tag = u16(e), type = u16(e + 2), value = type == 3 ? u16(e + 8) : u32(e + 8);
    if (tag == 256) width = static_cast<int>(value);
    if (tag == 257) height = value;
    if (tag == 259) compression = value;
    if (tag == 273) offset = value, strips = u32(e + 4);
    if (tag == 277) samples = value;
    if (tag == 279) count = value;
  }
  INFO("TIFF: width " << width << " height " << height << " compression " << compression << " strips " << strips);
  REQUIRE((compression == 1 && strips == 1 && samples == 3 && height == 1));
  REQUIRE(count == static_cast<uint32_t>(width) * 12);
  std::vector<float> px(static_cast<size_t>(width) * 3);
  std::memcpy(px.data(), b.data() + offset, count);
  return px;
}

}  // namespace

TEST_CASE("readers: the CLI's exports are the library's bytes (what the page downloads)", "[readers]") {
  const Passport& P = passport();
  for (const char* name : {"lut", "matrix"}) {
    const std::string j = P.dir + "/" + name;
    const Profile p = profile_from_json(slurp(j + ".json"));
    const std::vector<uint8_t> v4 = export_icc(p);
    IccOptions o2;
    o2.version = 2.4;
    const std::vector<uint8_t> v2 = export_icc(p, o2);
    CHECK(slurp(j + "_v4.icc") == std::string(v4.begin(), v4.end()));
    CHECK(slurp(j + "_v2.icc") == std::string(v2.begin(), v2.end()));
    CHECK(slurp(j + ".cube") == export_cube(p));
    // The same profile exports to the same bytes twice (fixed header date, no clock).
    CHECK(export_icc(p) == v4);
  }
}

TEST_CASE("readers: ICC LUT profiles in lcms2 (transicc), v4 and v2", "[readers][icc]") {
  need_tool("transicc", "liblcms2-utils");
  const Passport& P = passport();
  const PatchMatrix want = model_XYZ(P.lut, P.device, true);
  for (const char* v : {"v4", "v2"}) {
    const std::string icc = P.dir + "/lut_" + v + ".icc";
    compare(std::string("lcms2 transicc -t1, LUT ") + v, transicc(icc, P.device, 1), want, whites::D50(), 0.05, 0.3, true);
  }
}

TEST_CASE("readers: ICC LUT profile v2 in ArgyllCMS (xicclu -ff -ia -pX — iccdump)", "[readers][icc]") {
  need_tool("xicclu", "argyll");
  const Passport& P = passport();
  const std::string icc = P.dir + "/lut_v2.icc";
  // The profile white is D50, so ICC-absolute = relative here (wtpt = white = D50).
  compare("ArgyllCMS xicclu -ia, LUT v2", xicclu(icc, P.device, 'a'), model_XYZ(P.lut, P.device, true), whites::D50(), 0.05, 0.3, true);
  const std::string dump = run("iccdump -v 3 " + icc, true);
  INFO(dump.substr(0, 3000));
  CHECK(dump.find("Version      = 2.4.0") != std::string::npos);
  CHECK(dump.find("'mft2'") != std::string::npos);           // AToB0 is a lut16Type
  CHECK(dump.find("Input Table entries = 4096") != std::string::npos);
  CHECK(dump.find("CLUT resolution = " + std::to_string(IccOptions{}.grid_points)) != std::string::npos);
  CHECK(dump.find("'chad'") == std::string::npos);           // a v4 tag
  // Argyll 2.3.1's icclib refuses every v4 profile; when it stops doing so this tells us.
  const std::string v4 = run("iccdump " + P.dir + "/lut_v4.icc", true, false);
  INFO(v4);
  CHECK(v4.find("ICC V4 not supported") != std::string::npos);
}

TEST_CASE("readers: ICC matrix/shaper profiles are exact in lcms2 and ArgyllCMS", "[readers][icc]") {
  need_tool("transicc", "liblcms2-utils");
  need_tool("xicclu", "argyll");
  const Passport& P = passport();
  // The matrix profile's own device scale (its rgb_max equals the LUT profile's: same patches).
  REQUIRE(P.matrix.rgb_max == P.lut.rgb_max);
  const PatchMatrix want = model_XYZ(P.matrix, P.device, true);
  // s15Fixed16 colorants (2^-16) and the readers' printed digits (transicc: 4 decimals of Y = 100).
  for (const char* v : {"v4", "v2"})
    compare(std::string("lcms2 transicc -t1, matrix ") + v, transicc(P.dir + "/matrix_" + v + ".icc", P.device, 1), want,
            whites::D50(), 0.002, 0.01);
  compare("ArgyllCMS xicclu -ia, matrix v2", xicclu(P.dir + "/matrix_v2.icc", P.device, 'a'), want, whites::D50(), 0.002, 0.01);
}

TEST_CASE("readers: .cube (1D shaper + 3D LUT) in OpenColorIO (ociochecklut, ocioconvert)", "[readers][cube]") {
  need_tool("ociochecklut", "opencolorio-tools");
  need_tool("ocioconvert", "opencolorio-tools");
  const Passport& P = passport();
  const std::string cube = P.dir + "/lut.cube";
  const PatchMatrix want = model_XYZ(P.lut, P.device, false);
  // Every point through ocioconvert in one run: the device values as a float TIFF (our writer, read
  // by OpenImageIO), the result as PFM (read by our reader). The training patches also one by one
  // through ociochecklut, the reader, which must agree with ocioconvert.
  const int n = static_cast<int>(P.device.rows());
  std::vector<float> px(static_cast<size_t>(n) * 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) px[3 * static_cast<size_t>(i) + c] = static_cast<float>(P.device(i, c));
  const std::vector<uint8_t> tif = float_tiff(px.data(), n, 1, "device RGB");
  spit(P.dir + "/grid.tif", std::string(tif.begin(), tif.end()));
  run("ocioconvert --lut " + cube + " " + P.dir + "/grid.tif " + P.dir + "/grid_out.tif", true);
  int width = 0;
  const std::vector<float> out = read_float_tiff(slurp(P.dir + "/grid_out.tif"), width);
  REQUIRE(width == n);
  PatchMatrix got(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) got(i, c) = out[3 * static_cast<size_t>(i) + c];
  compare("OpenColorIO ocioconvert --lut, .cube", got, want, P.lut.white, 0.1, 0.5);
  double worst = 0;
  for (size_t i = 0; i < P.n_patches; ++i) {
    char args[160];
    std::snprintf(args, sizeof args, " %.9g %.9g %.9g", P.device(i, 0), P.device(i, 1), P.device(i, 2));
    // Without -v, ociochecklut prints the output triplet alone on its last line.
    const auto v = numbers_after(run("ociochecklut " + cube + args), "", "%lf %lf %lf");
    REQUIRE(v.size() == 1);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(v[0][c] - got(static_cast<Eigen::Index>(i), c)));
  }
  std::printf("OpenColorIO ociochecklut vs ocioconvert on the %zu training patches: worst |difference| %.2g (tolerance < 1e-5)\n",
              P.n_patches, worst);
  CHECK(worst < 1e-5);
}
#endif

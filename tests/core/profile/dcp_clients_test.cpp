// DNG camera profiles in the programs that load them (issue 46): RawTherapee's CLI renders the
// example Passport DNG with tristim's DCP, and the chart's patches in its 16-bit TIFF agree with
// what tristim's own profile predicts; so do they with tristim's ICC export as RawTherapee's input
// profile; ExifTool lists every tag with the values written. Native only: the clients are
// programs, installed by scripts/install-deps.sh (rawtherapee, libimage-exiftool-perl); a missing
// one fails.
//
// How RawTherapee is driven, and why:
//  - Settings and cache in the test's own folder (RT_SETTINGS, RT_CACHE), never the user's.
//  - A .pp3 with [Color Management] InputProfile=file:<the DCP>, DCPIlluminant (0 interpolate,
//    1/2 one illuminant), ApplyHueSatMap, no DCP tone curve / look table / exposure offset,
//    WorkingProfile ProPhoto and the ProPhoto output profile RTv4_Large; everything else neutral.
//  - The white balance is the profile's: a DNG reader white-balances with the camera neutral
//    (AsShotNeutral) before the ForwardMatrix (DNG 1.6 §6), so the test gives a copy of the DNG the
//    profile's neutral as AsShotNeutral (written by ExifTool) and RawTherapee WB "Camera" — what a
//    user gets by picking the white balance on the chart's white patch.
//  - Exposure: RawTherapee scales the raw to its white level (DNG units); tristim's XYZ are in the
//    reference's units (perfect diffuser Y = 100 at the training exposure). The compensation
//    log2(white level / max(camera white)) makes the two equal, so nothing is fitted to the output.
//  - Its 16-bit output is turned back into XYZ per pixel by lcms2 through the ICC profile embedded
//    in the TIFF (relative colorimetric, PCS D50), then sampled with tristim's own chart sampler
//    at the example's corners scaled to full resolution (x_full = 2·x_half − 4: RawTherapee's
//    output of this DNG lacks a 4-pixel border of the active area; measured by matching edges).
//  - tristim's side: the profile's prediction for the patches' camera RGB, Bradford-adapted to
//    D50 as the ForwardMatrix is (the relative-colorimetric rendering a DCP defines).
#ifndef __EMSCRIPTEN__
#include <Eigen/LU>
#include <lcms2.h>
#include <tiffio.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "shell.hpp"
#include "synthetic.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/io/json.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/profile/profile.hpp"

using namespace tristim;

namespace {

using test::slurp;
using test::spit;

std::string run(const std::string& cmd) { return test::run_shell(cmd + " 2>&1"); }

void need_tool(const char* tool, const char* package) {
  const bool found = std::system(("command -v " + std::string(tool) + " > /dev/null 2>&1").c_str()) == 0;
  if (!found) FAIL(tool << " is not installed (Debian package " << package << "): run scripts/install-deps.sh");
}

std::string q(const std::string& s) { return "'" + s + "'"; }

/// The Passport example through the CLI (sample, reference, fit, export), once per process.
struct Fixture {
  std::string dir;                       // absolute: the .pp3 names the DCP by its full path
  std::array<double, 8> corners{};       // examples/web/passport.json (measurement image)
  std::vector<std::string> ids;
  std::vector<bool> flagged;             // the sampler's flags (D6: dark)
  PatchMatrix rgb;                       // the patches' camera RGB (tristim's sampler on the RAW)
  double white_level = 0;                // the RAW's white level less black (RawTherapee's 1.0)
  std::map<std::string, Profile> profiles;
  ~Fixture() { std::system(("rm -rf " + q(dir)).c_str()); }
};

void build(Fixture& f) {
  f.dir = std::filesystem::absolute("tristim_dcp_clients_" + std::to_string(getpid())).string();
  std::filesystem::create_directories(f.dir + "/rt");
  const std::string cli = TRISTIM_CLI, d = f.dir + "/";
  const std::string dng = test::test_file_path(test::passport_dng);
  const json::Value preset = json::parse(slurp(test::test_file_path("examples/web/passport.json")));
  const auto c = preset.at("corners").as_numbers("corners");
  REQUIRE(c.size() == 8);
  std::string corners;
  for (int i = 0; i < 8; ++i) {
    f.corners[static_cast<size_t>(i)] = c[static_cast<size_t>(i)];
    corners += (i ? "," : "") + std::to_string(c[static_cast<size_t>(i)]);
  }
  run(cli + " sample " + q(dng) + " --chart passport --corners " + corners + " > " + d + "patches.csv");
  // References under D50, D65 and A; each profile's white is its illuminant's (--lab-white), so
  // its calibration illuminant is stated (D50, D65) or named at export (A: --illuminant A).
  for (const char* ill : {"D50", "D65", "A"})
    run(cli + " reference --chart passport --illuminant " + ill + " > " + d + "ref_" + ill + ".csv");
  const std::string white_A = "109.850,100,35.585";
  run(cli + " fit --rgb " + d + "patches.csv --xyz " + d + "ref_D50.csv --model matrix-3x3 --objective ls --out " + d + "m50.json");
  run(cli + " fit --rgb " + d + "patches.csv --xyz " + d +
      "ref_D50.csv --model Finlayson2015-2 --objective psm --out " + d + "rp50.json");
  run(cli + " fit --rgb " + d + "patches.csv --xyz " + d + "ref_D65.csv --lab-white D65 --model matrix-3x3 --objective ls --out " +
      d + "m65.json");
  run(cli + " fit --rgb " + d + "patches.csv --xyz " + d + "ref_A.csv --lab-white " + white_A +
      " --model matrix-3x3 --objective ls --out " + d + "mA.json");
  for (const char* name : {"m50", "rp50", "m65", "mA"})
    f.profiles[name] = profile_from_json(slurp(d + name + ".json"));
  const std::string model = " --camera-model 'Canon EOS Kiss X4'";
  run(cli + " export --profile " + d + "m50.json --dcp " + d + "m50.dcp --raw " + q(dng));
  run(cli + " export --profile " + d + "rp50.json --dcp " + d + "rp50.dcp" + model);
  run(cli + " export --profile " + d + "rp50.json --dcp " + d + "rp50_hsm.dcp --hue-sat-map 90,30,30" + model);
  run(cli + " export --profile " + d + "m65.json --second " + d + "mA.json --second-illuminant A --dcp " + d + "dual.dcp" +
      model);
  // A dual-illuminant profile whose illuminants differ as they do for a camera (two photos, under
  // A and under D65): the virtual Canon EOS 600D (the 550D's sensor; rawtoaces' sensitivities)
  // photographing the ColorChecker under each. The two Passport profiles above come from one photo
  // and share its neutral, which leaves a reader's neutral -> illuminant search nothing to tell.
  for (const char* ill : {"D65", "A"}) {
    run(cli + " simulate --camera Canon_EOS_600D --reflectances cc24 --illuminant " + ill + " > " + d + "sim_" + ill + ".csv");
    run(cli + " reference --chart cc24 --illuminant " + ill + " > " + d + "cc24_" + ill + ".csv");
  }
  run(cli + " fit --rgb " + d + "sim_D65.csv --xyz " + d + "cc24_D65.csv --lab-white D65 --model matrix-3x3 --out " + d + "v65.json");
  run(cli + " fit --rgb " + d + "sim_A.csv --xyz " + d + "cc24_A.csv --lab-white " + white_A + " --model matrix-3x3 --out " + d +
      "vA.json");
  run(cli + " export --profile " + d + "vA.json --illuminant A --second " + d + "v65.json --dcp " + d + "dual600.dcp" + model);
  for (const char* name : {"v65", "vA"}) f.profiles[name] = profile_from_json(slurp(d + name + ".json"));

  // The camera RGB of the patches, sampled by tristim from the RAW as `fit` was given them.
  const std::string raw = slurp(dng);
  const RawImage image = decode_any(reinterpret_cast<const std::uint8_t*>(raw.data()), raw.size());
  LayoutOptions layout;
  layout.chart = "passport";
  const ChartSample s = sample_chart(image, layout, f.corners);
  f.white_level = image.meta.saturation[1];
  f.rgb.resize(static_cast<Eigen::Index>(s.patches.size()), 3);
  for (size_t i = 0; i < s.patches.size(); ++i) {
    f.ids.push_back(s.patches[i].id);
    f.flagged.push_back(!s.patches[i].flags.empty());
    for (int k = 0; k < 3; ++k) f.rgb(static_cast<Eigen::Index>(i), k) = s.patches[i].mean[static_cast<size_t>(k)];
  }
}

Fixture& fixture() {
  static Fixture f;
  static const bool ready = (build(f), true);
  (void)ready;
  return f;
}

/// What RawTherapee renders, as XYZ relative to its PCS white (D50, Y = 1), per patch.
struct Render {
  std::vector<Vec3> xyz;
  Vec3 white;  // lcms2's D50
};

/// Reads a 16-bit RGB TIFF and its embedded ICC profile with libtiff.
void read_tiff16(const std::string& path, int& w, int& h, std::vector<std::uint16_t>& pixels, std::vector<std::uint8_t>& icc) {
  TIFF* t = TIFFOpen(path.c_str(), "r");
  REQUIRE(t != nullptr);
  std::uint32_t W = 0, H = 0;
  std::uint16_t bits = 0, spp = 0, planar = 1;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &W);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &H);
  TIFFGetField(t, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetField(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &planar);
  std::uint32_t icc_n = 0;
  void* icc_p = nullptr;
  const bool has_icc = TIFFGetField(t, TIFFTAG_ICCPROFILE, &icc_n, &icc_p) == 1;
  INFO(path << ": " << W << "x" << H << ", " << bits << " bits, " << spp << " samples");
  REQUIRE(bits == 16);
  REQUIRE(spp == 3);
  REQUIRE(planar == PLANARCONFIG_CONTIG);
  REQUIRE(has_icc);
  icc.assign(static_cast<std::uint8_t*>(icc_p), static_cast<std::uint8_t*>(icc_p) + icc_n);
  w = static_cast<int>(W);
  h = static_cast<int>(H);
  pixels.resize(static_cast<size_t>(W) * H * 3);
  for (std::uint32_t y = 0; y < H; ++y) REQUIRE(TIFFReadScanline(t, pixels.data() + static_cast<size_t>(y) * W * 3, y) == 1);
  TIFFClose(t);
}

/// Renders the example DNG with RawTherapee: `input` is the pp3's InputProfile value; the DNG's
/// AsShotNeutral is set to `neutral`; exposure compensation `ev`.
Render render(const std::string& name, const std::string& input, const Vec3& neutral, int dcp_illuminant, bool hue_sat_map,
              double ev) {
  need_tool("rawtherapee-cli", "rawtherapee");
  need_tool("exiftool", "libimage-exiftool-perl");
  const Fixture& f = fixture();
  const std::string d = f.dir + "/rt/" + name;
  run("cp " + q(test::test_file_path(test::passport_dng)) + " " + q(d + ".dng"));
  char ns[200];
  std::snprintf(ns, sizeof ns, "%.9f %.9f %.9f", neutral[0], neutral[1], neutral[2]);
  run("exiftool -q -overwrite_original -AsShotNeutral='" + std::string(ns) + "' " + q(d + ".dng"));
  char evs[40];
  std::snprintf(evs, sizeof evs, "%.6f", ev);
  spit(d + ".pp3", std::string("[Version]\nAppVersion=5.9\nVersion=346\n\n") +
                       "[Exposure]\nCompensation=" + evs + "\n\n"
                       "[White Balance]\nEnabled=true\nSetting=Camera\n\n"
                       "[Color Management]\nInputProfile=" + input + "\nToneCurve=false\nApplyLookTable=false\n"
                       "ApplyBaselineExposureOffset=false\nApplyHueSatMap=" + (hue_sat_map ? "true" : "false") +
                       "\nDCPIlluminant=" + std::to_string(dcp_illuminant) +
                       "\nWorkingProfile=ProPhoto\nOutputProfile=RTv4_Large\nOutputProfileIntent=Relative\nOutputBPC=false\n");
  const std::string log = run("RT_SETTINGS=" + q(f.dir + "/rt/settings") + " RT_CACHE=" + q(f.dir + "/rt/cache") +
                              " rawtherapee-cli -q -o " + q(d + ".tif") + " -p " + q(d + ".pp3") + " -t -b16 -Y -c " +
                              q(d + ".dng"));
  INFO("rawtherapee-cli: " << log);
  CHECK(log.find("DCP") == std::string::npos);  // RawTherapee names a DCP it cannot load or invert
  int w = 0, h = 0;
  std::vector<std::uint16_t> px;
  std::vector<std::uint8_t> icc;
  read_tiff16(d + ".tif", w, h, px, icc);
  REQUIRE(w == 1726);  // 1734 × 1156 active area less a 4-pixel border (see the header comment)
  REQUIRE(h == 1148);

  cmsHPROFILE in = cmsOpenProfileFromMem(icc.data(), static_cast<cmsUInt32Number>(icc.size()));
  REQUIRE(in != nullptr);
  cmsHPROFILE out = cmsCreateXYZProfile();
  cmsHTRANSFORM xf = cmsCreateTransform(in, TYPE_RGB_16, out, TYPE_XYZ_DBL, INTENT_RELATIVE_COLORIMETRIC, cmsFLAGS_NOCACHE);
  REQUIRE(xf != nullptr);
  RawImage img = test::blank_raw(w, h, 1e9);
  img.meta.layout = "rgb";
  img.meta.white_level = 1e9;
  std::vector<double> row(static_cast<size_t>(w) * 3);
  for (int y = 0; y < h; ++y) {
    cmsDoTransform(xf, px.data() + static_cast<size_t>(y) * w * 3, row.data(), static_cast<cmsUInt32Number>(w));
    for (size_t i = 0; i < row.size(); ++i) img.rgb[static_cast<size_t>(y) * w * 3 + i] = static_cast<float>(row[i]);
  }
  cmsDeleteTransform(xf);
  cmsCloseProfile(in);
  cmsCloseProfile(out);

  std::array<double, 8> c = f.corners;
  for (double& v : c) v = 2 * v - 4;
  LayoutOptions layout;
  layout.chart = "passport";
  const ChartSample s = sample_chart(img, layout, c);
  Render r;
  const cmsCIEXYZ* d50 = cmsD50_XYZ();
  r.white = Vec3(d50->X, d50->Y, d50->Z);
  REQUIRE(s.patches.size() == f.ids.size());
  for (size_t i = 0; i < s.patches.size(); ++i) {
    REQUIRE(s.patches[i].id == f.ids[i]);
    r.xyz.emplace_back(s.patches[i].mean[0], s.patches[i].mean[1], s.patches[i].mean[2]);
  }
  return r;
}

/// tristim's prediction for the patches, XYZ relative to D50 (Y = 1), Bradford-adapted from the
/// profile's white (as the DCP's ForwardMatrix adapts).
std::vector<Vec3> predicted(const Profile& p) {
  const PatchMatrix xyz = profile_predict(p, fixture().rgb);
  const DcpCalibration c = dcp_calibration(p, p.illuminant == "custom" ? "A" : "");
  const Vec3 white = c.linear * c.camera_white;
  const Mat3 cat = chromatic_adaptation_matrix(white / white[1], dcp_d50(), ChromaticAdaptation::Bradford);
  std::vector<Vec3> out;
  for (Eigen::Index i = 0; i < xyz.rows(); ++i) out.push_back(cat * xyz.row(i).transpose() / white[1]);
  return out;
}

/// RawTherapee's exposure compensation that puts its output in tristim's units: its data are
/// 1.0 at the white level (DNG units), tristim's perfect white is the model's camera white.
double exposure_ev(const Profile& p) {
  const DcpCalibration c = dcp_calibration(p, p.illuminant == "custom" ? "A" : "");
  return std::log2(fixture().white_level / c.camera_white.maxCoeff());
}

/// What a DNG reader renders for the patches by the specification's pipeline (dcp.hpp's reference:
/// neutral -> white xy -> interpolated matrices), at RawTherapee's scale (1 = white level) and
/// exposure; XYZ relative to D50.
std::vector<Vec3> pipeline(const Dcp& d, const Vec3& neutral, double ev, DcpTransform* used = nullptr) {
  const Fixture& f = fixture();
  const DcpTransform t = dcp_camera_to_xyz(d, neutral, 0);
  if (used) *used = t;
  std::vector<Vec3> out;
  for (Eigen::Index i = 0; i < f.rgb.rows(); ++i)
    out.push_back(dcp_render(d, t, f.rgb.row(i).transpose() / f.white_level) * std::exp2(ev));
  return out;
}

struct Delta {
  double mean = 0, max = 0;  // mean over every patch; max over those the sampler did not flag
  double max_all = 0;        // max over every patch (the flagged black D6 included)
  std::string worst;
  double y_ratio = 0;  // mean Y(RawTherapee) / Y(tristim): the exposure agreement
};

Delta compare(const Render& r, const std::vector<Vec3>& want) {
  const Fixture& f = fixture();
  Delta d;
  REQUIRE(r.xyz.size() == want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    const double de = delta_E_CIE2000(XYZ_to_Lab(r.xyz[i] * 100.0, r.white * 100.0), XYZ_to_Lab(want[i] * 100.0, dcp_d50() * 100.0));
    d.mean += de / static_cast<double>(want.size());
    d.y_ratio += r.xyz[i][1] / want[i][1] / static_cast<double>(want.size());
    d.max_all = std::max(d.max_all, de);
    if (!f.flagged[i] && de > d.max) {
      d.max = de;
      d.worst = f.ids[i];
    }
  }
  return d;
}

void report(const std::string& what, const Delta& d) {
  std::printf("rawtherapee: %-66s mean dE00 %.3f, max %.3f (%s; with D6 %.3f), Y ratio %.4f\n", what.c_str(), d.mean, d.max,
              d.worst.c_str(), d.max_all, d.y_ratio);
}

std::string file_input(const std::string& path) { return "file:" + path; }

/// A copy of a DCP with one change (a deliberately wrong profile).
std::string broken(const std::string& name, const std::function<void(Dcp&)>& change) {
  const Fixture& f = fixture();
  const std::string b = slurp(f.dir + "/" + name + ".dcp");
  Dcp d = read_dcp(reinterpret_cast<const std::uint8_t*>(b.data()), b.size());
  change(d);
  const std::vector<std::uint8_t> out = write_dcp(d);
  const std::string path = f.dir + "/broken_" + name + ".dcp";
  spit(path, std::string(out.begin(), out.end()));
  return path;
}

}  // namespace

TEST_CASE("dcp clients: RawTherapee renders the Passport DNG with tristim's single-illuminant DCP as the profile predicts",
          "[dcp][rawtherapee]") {
  Fixture& f = fixture();
  // A 3×3 profile: the DCP is the profile, exactly; what remains is RawTherapee's demosaicing of
  // the full-resolution image against tristim's half-size averages, largest in the darkest patches.
  {
    const Profile& p = f.profiles["m50"];
    const DcpCalibration c = dcp_calibration(p);
    const Delta d = compare(render("m50", file_input(f.dir + "/m50.dcp"), c.neutral, 1, true, exposure_ev(p)), predicted(p));
    report("matrix-3x3 ls D50 (ForwardMatrix1 only)", d);
    CHECK(d.mean < 0.5);
    CHECK(d.max < 1.0);
    CHECK(d.max_all < 2.5);
    CHECK(std::abs(d.y_ratio - 1) < 0.02);
  }
  // A root-polynomial: with its HueSatMap 90×30×30 the DCP follows the model; without, the linear
  // part at neutral alone is further off (printed and checked to be worse).
  {
    const Profile& p = f.profiles["rp50"];
    const DcpCalibration c = dcp_calibration(p);
    const Delta with = compare(render("rp50_hsm", file_input(f.dir + "/rp50_hsm.dcp"), c.neutral, 1, true, exposure_ev(p)), predicted(p));
    report("Finlayson2015-2 psm D50 + HueSatMap 90x30x30", with);
    const Delta off = compare(render("rp50_hsm_off", file_input(f.dir + "/rp50_hsm.dcp"), c.neutral, 1, false, exposure_ev(p)), predicted(p));
    report("the same DCP, ApplyHueSatMap=false", off);
    const Delta without = compare(render("rp50", file_input(f.dir + "/rp50.dcp"), c.neutral, 1, true, exposure_ev(p)), predicted(p));
    report("Finlayson2015-2 psm D50, no HueSatMap", without);
    CHECK(with.mean < 1.0);
    CHECK(with.max < 1.5);
    CHECK(std::abs(with.y_ratio - 1) < 0.02);
    CHECK(without.mean > with.mean);
    CHECK(off.mean > with.mean);
  }
}

TEST_CASE("dcp clients: RawTherapee reads both halves of tristim's dual-illuminant DCP and interpolates as DNG 1.6 says",
          "[dcp][rawtherapee]") {
  Fixture& f = fixture();
  // Each half at its own white balance: A (illuminant 1, the lower temperature) and D65.
  for (const auto& [name, half] : {std::pair<const char*, int>{"mA", 1}, {"m65", 2}}) {
    const Profile& p = f.profiles[name];
    const DcpCalibration c = dcp_calibration(p, p.illuminant == "custom" ? "A" : "");
    const Delta d = compare(render(std::string("dual_") + name, file_input(f.dir + "/dual.dcp"), c.neutral, half, true, exposure_ev(p)),
                            predicted(p));
    report(std::string("dual A + D65, DCPIlluminant=") + std::to_string(half) + ", at the white balance of " + name, d);
    CHECK(d.mean < 0.5);
    CHECK(d.max < 1.0);
  }
  // Interpolated (DCPIlluminant=0), the virtual 600D's dual DCP at three white balances: its A
  // neutral, its D65 neutral and the photo's own; RawTherapee against the specification's pipeline
  // (neutral -> xy through the interpolated ColorMatrices, weight in inverse CCT, mixed
  // ForwardMatrices).
  const std::string b = slurp(f.dir + "/dual600.dcp");
  const Dcp dual = read_dcp(reinterpret_cast<const std::uint8_t*>(b.data()), b.size());
  // One stop darker than the profiles' exposure: at the D65 balance the photo's white patch would
  // clip in RawTherapee's 16-bit output (the photo was lit nearer A).
  const double ev = exposure_ev(f.profiles["m50"]) - 1;
  const std::pair<const char*, Vec3> balances[] = {{"A (virtual 600D)", dcp_calibration(f.profiles["vA"], "A").neutral},
                                                   {"D65 (virtual 600D)", dcp_calibration(f.profiles["v65"]).neutral},
                                                   {"the photo's", dcp_calibration(f.profiles["m50"]).neutral}};
  double weights[3];
  int k = 0;
  for (const auto& [what, neutral] : balances) {
    DcpTransform t;
    const std::vector<Vec3> want = pipeline(dual, neutral, ev, &t);
    weights[k] = t.weight1;
    const Delta d = compare(render("dual600_" + std::to_string(k), file_input(f.dir + "/dual600.dcp"), neutral, 0, true, ev), want);
    char label[160];
    std::snprintf(label, sizeof label, "600D A + D65 interpolated at %s white balance (weight of A %.3f)", what, t.weight1);
    report(label, d);
    CHECK(d.mean < 0.5);
    CHECK(d.max < 1.0);
    ++k;
  }
  CHECK(weights[0] > 0.98);
  CHECK(weights[1] < 0.02);
  CHECK(weights[2] > 0.05);
  CHECK(weights[2] < 0.95);
}

TEST_CASE("dcp clients: a deliberately wrong DCP or white balance shows in RawTherapee as a large error", "[dcp][rawtherapee]") {
  Fixture& f = fixture();
  const Profile& p = f.profiles["m50"];
  const DcpCalibration c = dcp_calibration(p);
  const std::vector<Vec3> want = predicted(p);
  const double ev = exposure_ev(p);
  const Delta right = compare(render("right", file_input(f.dir + "/m50.dcp"), c.neutral, 1, true, ev), want);
  // ForwardMatrix written column by column (transposed).
  const std::string transposed = broken("m50", [](Dcp& d) { d.forward_matrix1.transposeInPlace(); });
  const Delta t = compare(render("wrong_transposed", file_input(transposed), c.neutral, 1, true, ev), want);
  report("WRONG: ForwardMatrix1 transposed", t);
  CHECK(t.mean > 3);
  CHECK(t.mean > 10 * right.mean);
  // The matrix the other way round: XYZ -> camera stored as the ForwardMatrix.
  const std::string inverted = broken("m50", [](Dcp& d) {
    Mat3 m = d.forward_matrix1.inverse();
    const Vec3 s = m * Vec3::Ones(), w = dcp_d50();
    for (int r = 0; r < 3; ++r) m.row(r) *= w[r] / s[r];
    d.forward_matrix1 = m;
  });
  const Delta i = compare(render("wrong_direction", file_input(inverted), c.neutral, 1, true, ev), want);
  report("WRONG: ForwardMatrix1 in the XYZ -> camera direction", i);
  CHECK(i.mean > 10);
  // The right DCP under another white balance: the multipliers (1/neutral) given as the neutral.
  const Vec3 multipliers = c.neutral.cwiseInverse() / c.neutral.cwiseInverse().maxCoeff();
  const Delta wb = compare(render("wrong_wb", file_input(f.dir + "/m50.dcp"), multipliers, 1, true, ev), want);
  report("WRONG: white balance (multipliers given as the neutral)", wb);
  CHECK(wb.mean > 10);
  // Calibration illuminant tag A on a D50 profile: with one illuminant a reader uses the one
  // ForwardMatrix whatever the tag says, so this must NOT change the rendering.
  const std::string tag = broken("m50", [](Dcp& d) { d.illuminant1 = 17; });
  const Delta same = compare(render("same_illuminant_tag", file_input(tag), c.neutral, 1, true, ev), want);
  report("single illuminant tagged A instead of D50 (no effect expected)", same);
  CHECK(same.mean == Approx(right.mean).margin(1e-3));
}

TEST_CASE("dcp clients: ExifTool lists every DCP tag with the values written", "[dcp][exiftool]") {
  need_tool("exiftool", "libimage-exiftool-perl");
  Fixture& f = fixture();
  for (const char* name : {"m50", "rp50_hsm", "dual"}) {
    const std::string path = f.dir + "/" + name + ".dcp";
    const std::string b = slurp(path);
    const Dcp d = read_dcp(reinterpret_cast<const std::uint8_t*>(b.data()), b.size());
    // -m: ExifTool skips a tag of more than its count limit with a "[Minor]" warning unless told to
    // take it (a 90×30×30 table has 243,000 floats; Adobe's own maps are as large).
    const json::Value all = json::parse(run("exiftool -m -j -n -G1 " + q(path)));
    REQUIRE(all.is_array());
    const json::Value& t = all.as_array().at(0);
    INFO(name << ": " << t.dump());
    CHECK(t.at("File:FileType").as_string() == "DCP");
    CHECK(t.at("File:ExifByteOrder").as_string() == "II");
    CHECK(t.at("IFD0:UniqueCameraModel").as_string() == d.unique_camera_model);
    CHECK(t.at("IFD0:ProfileName").as_string() == d.profile_name);
    CHECK(t.at("IFD0:ProfileCopyright").as_string() == d.copyright);
    CHECK(t.at("IFD0:ProfileCalibrationSig").as_string() == "tristim");
    CHECK(t.at("IFD0:ProfileEmbedPolicy").as_number() == 0);
    CHECK(t.at("IFD0:CalibrationIlluminant1").as_number() == d.illuminant1);
    auto matrix = [&](const char* key, const Mat3& m) {
      std::vector<double> v;
      std::istringstream ss(t.at(key).as_string(key));
      double x;
      while (ss >> x) v.push_back(x);
      REQUIRE(v.size() == 9);
      for (int k = 0; k < 9; ++k) CHECK(v[static_cast<size_t>(k)] == Approx(m(k / 3, k % 3)).margin(1e-6));
    };
    matrix("IFD0:ColorMatrix1", d.color_matrix1);
    matrix("IFD0:ForwardMatrix1", d.forward_matrix1);
    if (d.dual()) {
      CHECK(t.at("IFD0:CalibrationIlluminant2").as_number() == d.illuminant2);
      matrix("IFD0:ColorMatrix2", d.color_matrix2);
      matrix("IFD0:ForwardMatrix2", d.forward_matrix2);
      CHECK(d.illuminant1 == 17);  // A, the lower colour temperature, first
      CHECK(d.illuminant2 == 21);  // D65
    } else {
      CHECK(t.find("IFD0:ColorMatrix2") == nullptr);
      CHECK(t.find("IFD0:ForwardMatrix2") == nullptr);
      CHECK(t.find("IFD0:CalibrationIlluminant2") == nullptr);
    }
    if (!d.hue_sat_map.empty()) {
      CHECK(t.at("IFD0:ProfileHueSatMapDims").as_string() == "90 30 30");
      CHECK(t.at("IFD0:ProfileHueSatMapEncoding").as_number() == 0);
      CHECK(t.find("IFD0:ProfileHueSatMapData1") != nullptr);
      CHECK(t.find("IFD0:ProfileHueSatMapData2") == nullptr);
    } else {
      CHECK(t.find("IFD0:ProfileHueSatMapDims") == nullptr);
      CHECK(t.find("IFD0:ProfileHueSatMapData1") == nullptr);
    }
    CHECK(t.find("IFD0:ProfileLookTableDims") == nullptr);
    CHECK(t.find("IFD0:ProfileToneCurve") == nullptr);
    CHECK(t.find("ExifTool:Warning") == nullptr);
    // Every tag's number and type as ExifTool's verbose listing decodes them (0xc621 = 50721 …).
    const std::string v = run("exiftool -m -v2 " + q(path));
    std::map<std::string, std::string> want = {
        {"0xc614", "string"},       {"0xc621", "rational64s[9]"}, {"0xc65a", "int16u[1]"}, {"0xc6f4", "string[8]"},
        {"0xc6f8", "string"},       {"0xc6fd", "int32u[1]"},      {"0xc6fe", "string"},    {"0xc714", "rational64s[9]"}};
    if (d.dual()) {
      want["0xc622"] = "rational64s[9]";
      want["0xc65b"] = "int16u[1]";
      want["0xc715"] = "rational64s[9]";
    }
    if (!d.hue_sat_map.empty()) {
      want["0xc6f9"] = "int32u[3]";
      want["0xc6fa"] = "float[243000]";
      want["0xc7a3"] = "int32u[1]";
    }
    for (const auto& [tag, type] : want) {
      INFO("tag " << tag << " as " << type);
      CHECK(v.find("Tag " + tag + " (") != std::string::npos);
      CHECK(std::regex_search(v, std::regex("Tag " + tag + " \\([0-9]+ bytes, " + std::regex_replace(type, std::regex("[\\[\\]]"), "\\$&"))));
    }
    CHECK(static_cast<int>(std::count(v.begin(), v.end(), '\n')) > 0);
    const std::regex tag_line("Tag 0x[0-9a-f]{4} \\(");
    CHECK(static_cast<size_t>(std::distance(std::sregex_iterator(v.begin(), v.end(), tag_line), std::sregex_iterator())) == want.size());
  }
}
TEST_CASE("dcp clients: RawTherapee renders the Passport DNG with tristim's ICC as input profile as the profile predicts",
          "[icc][rawtherapee]") {
  // RawTherapee applies an input ICC profile to its camera data after its white balance: with the
  // neutral (1,1,1) as AsShotNeutral ("UniWB") those are the raw camera RGB over its white level,
  // which the ICC's device value 1.0 must be (export --rgb-scale <white level>). The PCS is D50 with
  // the profile white adapted (Bradford), as the DCP's is: the same prediction holds.
  Fixture& f = fixture();
  const std::string cli = TRISTIM_CLI, d = f.dir + "/";
  char wl[64];
  std::snprintf(wl, sizeof wl, "%.3f", f.white_level);
  for (const char* name : {"m50", "rp50"}) {
    const Profile& p = f.profiles[name];
    for (const char* version : {"4.3", "2.4"}) {
      const std::string icc = d + name + "_" + version + ".icc";
      run(cli + " export --profile " + d + name + ".json --icc " + icc + " --icc-version " + version + " --rgb-scale " + wl);
      const Delta r = compare(render(std::string("icc_") + name + "_" + version, file_input(icc), Vec3(1, 1, 1), 0, false, 0), predicted(p));
      report(std::string("ICC v") + version + " of " + (std::string(name) == "m50" ? "matrix-3x3 (matrix/shaper)" : "Finlayson2015-2 (LUT)"), r);
      CHECK(r.mean < 0.6);
      CHECK(r.max < 1.0);
      CHECK(std::abs(r.y_ratio - 1) < 0.02);
    }
  }
}
#endif

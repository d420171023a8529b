// `tristim apply` with this image's own frame calibration (Abed 2013 App. C step 8): the light trap
// measured in the image, dark frames and flat field go through the same code as `sample`
// (frame_calibration, core/cli/cmd_raw.cpp). Driven through the CLI as a user would (native only).
#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
#include <unistd.h>

#include <cmath>
#include <cstdlib>

#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/profile.hpp"

using namespace tristim;
using namespace tristim::test;

TEST_CASE("apply --light-trap / --dark: the image's own flare and dark are subtracted before the profile",
          "[characterisation][apply][cli]") {
  const std::string cli = TRISTIM_CLI, dng = std::string(TRISTIM_SOURCE_DIR) + "/examples/web/passport.dng";
  const std::string d = "tristim_apply_cal_" + std::to_string(getpid()) + "/";
  std::system(("mkdir -p " + d).c_str());
  run_shell(cli + " sample " + dng + " --chart passport --corners 335,291,649,285,649,486,328,488 > " + d + "patches.csv");
  run_shell(cli + " reference --chart passport --illuminant D50 > " + d + "reference.csv");
  run_shell(cli + " fit --rgb " + d + "patches.csv --xyz " + d + "reference.csv --model matrix-3x3 --out " + d + "p.json 2>/dev/null");
  const std::string trap = "603,443,643,443,643,481,603,481";  // the black patch D6 marked as the trap
  run_shell(cli + " apply " + d + "p.json " + dng + " --out " + d + "plain.pfm 2>/dev/null");
  run_shell(cli + " apply " + d + "p.json " + dng + " --light-trap " + trap + " --out " + d + "trap.pfm 2>/dev/null");
  run_shell(cli + " apply " + d + "p.json " + dng + " --dark " + dng + " --out " + d + "dark.pfm 2>/dev/null");
  const Profile p = profile_from_json(slurp(d + "p.json"));
  const Image3f plain = read_pfm(slurp(d + "plain.pfm")), with_trap = read_pfm(slurp(d + "trap.pfm")),
                dark = read_pfm(slurp(d + "dark.pfm"));
  // The flare measured independently on the decoded image: the trap output is M·(RGB − flare).
  const std::string bytes = slurp(dng);
  const RawImage image = decode_any(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  std::array<double, 8> corners{603, 443, 643, 443, 643, 481, 603, 481};
  const LightTrap t = measure_light_trap(image, corners);
  const Vec3 flare(t.mean[0], t.mean[1], t.mean[2]);
  REQUIRE(flare.norm() > 0);
  const Vec3 shift = p.model.coefficients.leftCols<3>() * flare;
  REQUIRE(plain.pixels.size() == with_trap.pixels.size());
  double worst = 0, worst_dark = 0;
  for (size_t i = 0; i < plain.pixels.size(); ++i) {
    const double expected = plain.pixels[i] - shift[i % 3];
    worst = std::max(worst, std::fabs(with_trap.pixels[i] - expected) / (1 + std::fabs(expected)));
    worst_dark = std::max(worst_dark, static_cast<double>(std::fabs(dark.pixels[i])));
  }
  INFO("flare " << flare.transpose() << ", worst relative difference " << worst);
  CHECK(worst < 1e-5);
  CHECK(worst_dark == 0);  // the image as its own dark frame leaves nothing
  // A PFM has no frames to calibrate; a trap needs 8 numbers.
  const std::string err = run_shell(cli + " apply " + d + "p.json " + d + "plain.pfm --light-trap " + trap + " --out " + d +
                                        "x.pfm 2>&1; echo rc=$?", false);
  CHECK(err.find("INVALID_ARGUMENT") != std::string::npos);
  CHECK(err.find("rc=1") != std::string::npos);
  const std::string err2 = run_shell(cli + " apply " + d + "p.json " + dng + " --light-trap 1,2,3 --out " + d +
                                         "x.pfm 2>&1; echo rc=$?", false);
  CHECK(err2.find("light-trap needs 8 numbers") != std::string::npos);
  std::system(("rm -rf " + d).c_str());
}
#endif

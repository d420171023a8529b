#include <algorithm>
#include <sstream>

#include "test_support.hpp"
#include "tristim/colorimetry.hpp"

using namespace tristim;

TEST_CASE("CIEDE2000 reproduces the Sharma, Wu & Dalal (2005) test pairs to 1e-4", "[colorimetry][de2000]") {
  std::istringstream in(test::read_shared("colour-science/test-expectations/ciede2000_sharma2005_test_pairs.csv"));
  std::string line;
  std::getline(in, line);  // header: pair,L1,a1,b1,L2,a2,b2,dE00
  int n = 0;
  double worst = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double id, L1, a1, b1, L2, a2, b2, expected;
    row >> id >> L1 >> a1 >> b1 >> L2 >> a2 >> b2 >> expected;
    const double got = delta_E_CIE2000(Vec3(L1, a1, b1), Vec3(L2, a2, b2));
    const double sym = delta_E_CIE2000(Vec3(L2, a2, b2), Vec3(L1, a1, b1));
    INFO("pair " << id << ": expected " << expected << ", got " << got);
    CHECK(std::abs(got - expected) <= 1e-4 + 1e-12);
    CHECK(std::abs(sym - expected) <= 1e-4 + 1e-12);
    worst = std::max(worst, std::abs(got - expected));
    ++n;
  }
  INFO("worst |dE00 - published| = " << worst);
  CHECK(n == 33);
}

TEST_CASE("Lab <-> XYZ round trip on a grid, 1e-10", "[colorimetry]") {
  const Vec3 white = whites::D50();
  double worst = 0;
  for (double L = 0; L <= 100; L += 5)
    for (double a = -100; a <= 100; a += 20)
      for (double b = -100; b <= 100; b += 20) {
        const Vec3 Lab(L, a, b);
        const Vec3 back = XYZ_to_Lab(Lab_to_XYZ(Lab, white), white);
        worst = std::max(worst, (back - Lab).cwiseAbs().maxCoeff());
      }
  INFO("worst " << worst);
  CHECK(worst < 1e-10);
}

TEST_CASE("white maps to L*=100, a*=b*=0 and xyY round-trips", "[colorimetry]") {
  const Vec3 Lab = XYZ_to_Lab(whites::D65(), whites::D65());
  CHECK(Lab[0] == Approx(100).margin(1e-12));
  CHECK(std::abs(Lab[1]) < 1e-12);
  CHECK(std::abs(Lab[2]) < 1e-12);
  const Vec3 XYZ(20.0, 30.0, 40.0);
  CHECK((xyY_to_XYZ(XYZ_to_xyY(XYZ)) - XYZ).norm() < 1e-12);
  const Vec3 LCh = Lab_to_LCh(Vec3(50, -20, -30));
  CHECK((LCh_to_Lab(LCh) - Vec3(50, -20, -30)).norm() < 1e-12);
}

TEST_CASE("chromatic adaptation maps the source white onto the destination white", "[colorimetry]") {
  for (auto m : {ChromaticAdaptation::Bradford, ChromaticAdaptation::CAT02, ChromaticAdaptation::VonKries}) {
    const Mat3 M = chromatic_adaptation_matrix(whites::D65(), whites::D50(), m);
    CHECK((M * whites::D65() - whites::D50()).norm() < 1e-9);
  }
  // Bradford D65 -> D50 as published by Lindbloom (3 decimals shown there).
  const Mat3 M = chromatic_adaptation_matrix(whites::D65(), whites::D50());
  CHECK(M(0, 0) == Approx(1.0478).margin(2e-4));
  CHECK(M(0, 1) == Approx(0.0229).margin(2e-4));
  CHECK(M(2, 2) == Approx(0.7521).margin(2e-4));
}

TEST_CASE("XYZ -> sRGB: D65 white is (1,1,1), black is 0", "[colorimetry]") {
  const Vec3 w = XYZ_to_sRGB(whites::D65() / 100.0);
  CHECK((w - Vec3(1, 1, 1)).cwiseAbs().maxCoeff() < 2e-4);
  CHECK(XYZ_to_sRGB(Vec3(0, 0, 0)).norm() == 0.0);
}

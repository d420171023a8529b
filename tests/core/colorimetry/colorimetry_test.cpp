#include <algorithm>
#include <sstream>

#include "test_support.hpp"
#include "tristim/colorimetry/colorimetry.hpp"

#include <Eigen/LU>

using namespace tristim;

TEST_CASE("CIEDE2000 reproduces the Sharma, Wu & Dalal (2005) test pairs to 1e-4", "[colorimetry][de2000]") {
  std::istringstream in(test::read_test_file("tests/data/colour-science/ciede2000_sharma2005_test_pairs.csv"));
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
    // The components and rotation term rebuild eq (22): dE² = dL² + dC² + dH² + RT·dC·dH.
    const DeltaE2000 c = delta_E_CIE2000_components(Vec3(L1, a1, b1), Vec3(L2, a2, b2));
    CHECK(std::abs(c.RT) <= 2.0);
    CHECK(c.dE * c.dE == Approx(c.dL * c.dL + c.dC * c.dC + c.dH * c.dH + c.RT * c.dC * c.dH).margin(1e-12));
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

TEST_CASE("dE76, dE94 and dE2000 match colour-science's expected values (1e-7)", "[colorimetry]") {
  // colour/difference/tests/test_delta_e.py (colour-science; transcribed here, tests/data/SOURCES.md).
  const Vec3 ref(100.0, 21.57210357, 272.2281935);
  const Vec3 s1(100.0, 426.67945353, 72.39590835), s2(100.0, 74.05216981, 276.45318193),
      s3(100.0, 8.32281957, -73.58297716);
  CHECK(delta_E_CIE1976(ref, s1) == Approx((s1 - ref).norm()).margin(1e-12));
  CHECK(delta_E_CIE1976(ref, s2) == Approx(52.64986116).margin(1e-7));
  CHECK(delta_E_CIE1994(ref, s1) == Approx(83.7792255008871).margin(1e-7));
  CHECK(delta_E_CIE1994(ref, s2) == Approx(10.053931954553839).margin(1e-7));
  CHECK(delta_E_CIE1994(ref, s3) == Approx(57.535453706667425).margin(1e-7));
  CHECK(delta_E_CIE1994(ref, s1, true) == Approx(88.3355530575065).margin(1e-7));
  CHECK(delta_E_CIE1994(ref, s2, true) == Approx(10.612657890048272).margin(1e-7));
  CHECK(delta_E_CIE1994(ref, s3, true) == Approx(60.36868726106333).margin(1e-7));
  CHECK(delta_E_CIE2000(ref, s1) == Approx(94.03564903).margin(1e-7));
  CHECK(delta_E_CIE2000(ref, s2) == Approx(14.87906419).margin(1e-7));
  CHECK(delta_E_CIE2000(ref, s3) == Approx(68.23111251).margin(1e-7));
  // colour's textiles=True for CIE2000 means kL = 2.
  CHECK(delta_E_CIE2000(ref, Vec3(50.0, 426.67945353, 72.39590835), 2) == Approx(95.79205352).margin(1e-7));
  CHECK(delta_E_CIE2000(ref, Vec3(50.0, 74.05216981, 276.45318193), 2) == Approx(23.55420943).margin(1e-7));
  CHECK(delta_E_CIE2000(ref, Vec3(50.0, 8.32281957, -73.58297716), 2) == Approx(70.63213819).margin(1e-7));
}

TEST_CASE("delta_E over rows by method id: colour-science's values per pair, coded errors", "[colorimetry]") {
  // The same colour-science expectations as above, through the list form the page calls (deltaE).
  const Vec3 ref(100.0, 21.57210357, 272.2281935);
  const std::vector<Vec3> refs{ref, ref}, samples{Vec3(100.0, 74.05216981, 276.45318193), Vec3(100.0, 8.32281957, -73.58297716)};
  const auto d00 = delta_E("CIE2000", refs, samples), d94 = delta_E("CIE1994", refs, samples),
             d76 = delta_E("CIE1976", refs, samples);
  REQUIRE(d00.size() == 2);
  CHECK(d00[0] == Approx(14.87906419).margin(1e-7));
  CHECK(d00[1] == Approx(68.23111251).margin(1e-7));
  CHECK(d94[0] == Approx(10.053931954553839).margin(1e-7));
  CHECK(d94[1] == Approx(57.535453706667425).margin(1e-7));
  CHECK(d76[0] == Approx(52.64986116).margin(1e-7));
  test::require_code([&] { delta_E("CIE2001", refs, samples); }, ErrorCode::UnknownId);
  test::require_code([&] { delta_E("CIE2000", refs, {ref}); }, ErrorCode::InvalidArgument);
  const auto Lab = each_row<&XYZ_to_Lab>({whites::D65(), Vec3::Zero()}, whites::D65());
  CHECK(Lab[0].isApprox(Vec3(100, 0, 0), 1e-12));
  CHECK(Lab[1].norm() == Approx(0).margin(1e-12));
}

TEST_CASE("Bradford D65 -> D50 matches Lindbloom's published matrix — CAT02 and von Kries differ from it", "[colorimetry]") {
  // B. Lindbloom, "Chromatic Adaptation" (whites D65 = 0.95047, 1, 1.08883; D50 = 0.96422, 1, 0.82521).
  const Vec3 d65(0.95047, 1.0, 1.08883), d50(0.96422, 1.0, 0.82521);
  Mat3 bradford;
  bradford << 1.0478112, 0.0228866, -0.0501270, 0.0295424, 0.9904844, -0.0170491, -0.0092345, 0.0150436, 0.7521316;
  const Mat3 b = chromatic_adaptation_matrix(d65, d50, ChromaticAdaptation::Bradford);
  INFO("Bradford\n" << b);
  CHECK((b - bradford).cwiseAbs().maxCoeff() < 1e-6);
  // Each transform is diagonal in its own cone space, so the three must differ off the diagonal.
  const Mat3 c = chromatic_adaptation_matrix(d65, d50, ChromaticAdaptation::CAT02);
  const Mat3 v = chromatic_adaptation_matrix(d65, d50, ChromaticAdaptation::VonKries);
  CHECK((c - b).cwiseAbs().maxCoeff() > 1e-3);
  CHECK((v - b).cwiseAbs().maxCoeff() > 1e-3);
  // Adapting there and back is the identity.
  const Mat3 back = chromatic_adaptation_matrix(d50, d65, ChromaticAdaptation::CAT02) * c;
  CHECK((back - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("XYZ -> sRGB matches the IEC 61966-2-1 matrix and transfer function", "[colorimetry]") {
  // IEC 61966-2-1:1999 publishes XYZ -> linear sRGB to 4 decimals.
  Mat3 iec;
  iec << 3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570;
  const Mat3 inv = sRGB_to_XYZ_matrix().inverse();
  INFO(inv);
  CHECK((inv - iec).cwiseAbs().maxCoeff() < 5e-4);
  // Transfer function: 12.92·L up to L = 0.0031308, then 1.055·L^(1/2.4) − 0.055 (0.5 -> 0.735357).
  const Mat3 M = sRGB_to_XYZ_matrix();
  CHECK(XYZ_to_sRGB(M * Vec3(0.5, 0.5, 0.5))[1] == Approx(0.7353569831).margin(1e-9));
  CHECK(XYZ_to_sRGB(M * Vec3(0.0031308, 0.0031308, 0.0031308))[0] == Approx(12.92 * 0.0031308).margin(1e-9));
  CHECK((XYZ_to_sRGB(M.col(0), false) - Vec3(1, 0, 0)).norm() < 1e-12);
}

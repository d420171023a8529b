// ACES IDT (profile/idt.hpp): a planted matrix, colour-science's published matrices for the Canon
// EOS 5D Mark II under D55 and ISO 7589 tungsten (CAT02 and Bradford), the chart path, refusals.
#include <cmath>
#include <cstdio>
#include <random>

#include "test_support.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/idt.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

// colour-science/colour commit 9d743142ed97a5cfae347b559aca14c43464eb70 (2024-10-11),
// colour/characterisation/tests/test_aces_it.py, TestMatrixIdt.test_matrix_idt: matrix_idt of the
// rawtoaces v1 Canon 5D Mk II sensitivities with the 190 training patches (BFGS), atol 1e-4. Its
// comments give rawtoaces v1's own matrices (Ceres) for the same camera, which agree to ~3e-5.
const double kD55_CAT02[9] = {0.86498930, -0.02627499, 0.16128570, 0.05654629, 1.12305999,
                              -0.17960629, 0.02369089, -0.20253026, 1.17883937};
const double kTungsten_CAT02[9] = {0.88849143, -0.07750529, 0.18901385, 0.02180460, 1.06661379,
                                   -0.08841839, -0.01971799, -0.20666347, 1.22638146};
const double kD55_Bradford[9] = {0.86507763, -0.02407809, 0.15900045, 0.05633306, 1.12612394,
                                 -0.18245700, 0.02450723, -0.20931423, 1.18480700};
const double kD55_rawtoaces[9] = {0.864994, -0.026302, 0.161308, 0.056527, 1.122997, -0.179524, 0.023683, -0.202547, 1.178864};
const double kTungsten_rawtoaces[9] = {0.888492, -0.077505, 0.189014, 0.021805, 1.066614, -0.088418, -0.019718, -0.206664, 1.226381};
// test_white_balance_multipliers: D55 -> (2.34141541, 1, 1.51633759).

SpectralData canon_5d2() {
  const char* p = "tests/data/colour-science/camera_canon_eos_5d_mark_ii_rawtoaces_v1_scitech_380-780_5nm.csv";
  return read_ssf_csv(test::read_test_file(p), p);
}

void check_matrix(const Mat3& got, const double* want, double tol, const char* what, const char* who = "colour-science") {
  double worst = 0;
  int wi = 0;
  for (int i = 0; i < 9; ++i) {
    const double d = std::abs(got(i / 3, i % 3) - want[i]);
    if (d > worst) worst = d, wi = i;
  }
  std::printf("IDT %s vs %s: worst |difference| %.2e at (%d,%d): %.8f vs %.8f (tolerance %.0e)\n", what, who,
              worst, wi / 3, wi % 3, got(wi / 3, wi % 3), want[wi], tol);
  CHECK(worst <= tol);
}

}  // namespace

TEST_CASE("idt: a planted matrix with rows summing to one is recovered", "[idt]") {
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(0.02, 1.0), off(-0.2, 0.2);
  Mat3 B;
  for (int i = 0; i < 3; ++i) {
    B(i, 0) = (i == 0 ? 0.9 : 0.0) + off(rng);
    B(i, 1) = (i == 1 ? 0.9 : 0.0) + off(rng);
    B(i, 2) = 1.0 - B(i, 0) - B(i, 1);
  }
  const Mat3 N = aces2065_1_to_XYZ();
  std::vector<Vec3> rgb, xyz;
  for (int p = 0; p < 60; ++p) {
    rgb.emplace_back(u(rng), u(rng), u(rng));
    xyz.push_back(N * B * rgb.back());
  }
  const IdtResult r = fit_idt(rgb, xyz, Vec3(2, 1, 1.5));
  INFO("planted\n" << B << "\nfitted\n" << r.matrix);
  CHECK((r.matrix - B).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(r.max_delta_E76 < 1e-7);
  CHECK(r.status == "ok");
  CHECK((r.matrix * Vec3::Ones() - Vec3::Ones()).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((r.camera_matrix() - B * Vec3(2, 1, 1.5).asDiagonal()).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("idt: ACES2065-1 primaries matrix is SMPTE ST 2065-1's", "[idt]") {
  // ST 2065-1 / TB-2014-004 published NPM.
  const double want[9] = {0.9525523959, 0.0, 0.0000936786, 0.3439664498, 0.7281660966, -0.0721325464, 0.0, 0.0, 1.0088251844};
  const Mat3 N = aces2065_1_to_XYZ();
  for (int i = 0; i < 9; ++i) CHECK(std::abs(N(i / 3, i % 3) - want[i]) < 1e-9);
}

TEST_CASE("idt: Canon 5D Mk II matches colour-science's matrix_idt to 1e-4", "[idt]") {
  const SpectralData ssf = canon_5d2();
  SECTION("D55, CAT02") {
    const IdtResult r = idt_from_sensitivities(ssf, illuminant_spd("D55"), idt_training_190());
    check_matrix(r.matrix, kD55_CAT02, 1e-4, "D55 CAT02");
    check_matrix(r.matrix, kD55_rawtoaces, 1e-4, "D55 CAT02", "rawtoaces v1 (Ceres)");
    CHECK(std::abs(r.white_balance[0] - 2.34141541) < 1e-6);
    CHECK(r.white_balance[1] == 1.0);
    CHECK(std::abs(r.white_balance[2] - 1.51633759) < 1e-6);
    CHECK(r.patches == 190);
    CHECK(r.adaptation == "CAT02");
    // colour's additional_data: the grey patch 4 (reflectance 0.1995) is (0.1995, 0.1995, 0.1995).
    CHECK((r.white_balanced_RGB[3] - Vec3::Constant(0.1995)).cwiseAbs().maxCoeff() < 1e-7);
    CHECK(std::abs(r.white_balanced_RGB[0][0] - 0.02075823) < 1e-7);
    CHECK(std::abs(r.target_XYZ[0][0] - 0.01743160) < 1e-7);
    CHECK(std::abs(r.target_XYZ[2][2] - 0.78350814) < 1e-7);
  }
  SECTION("D55, Bradford") {
    IdtOptions o;
    o.adaptation = ChromaticAdaptation::Bradford;
    const IdtResult r = idt_from_sensitivities(ssf, illuminant_spd("D55"), idt_training_190(), o);
    check_matrix(r.matrix, kD55_Bradford, 1e-4, "D55 Bradford");
  }
  SECTION("AMPAS ISO 7589 studio tungsten, CAT02") {
    const char* p = "tests/data/colour-science/illuminant_ampas_iso7589_studio_tungsten_380-780_5nm.csv";
    const SpectralData ill = read_illuminant_csv(test::read_test_file(p), p);
    const IdtResult r = idt_from_sensitivities(ssf, ill, idt_training_190());
    check_matrix(r.matrix, kTungsten_CAT02, 1e-4, "ISO 7589 tungsten CAT02");
    check_matrix(r.matrix, kTungsten_rawtoaces, 1e-4, "ISO 7589 tungsten CAT02", "rawtoaces v1 (Ceres)");
  }
}

TEST_CASE("idt: from a chart's patches, the spectral truth is recovered", "[idt]") {
  // The virtual camera photographs the 190 patches; the chart path sees camera RGB (arbitrary
  // exposure, no white balance) and the references' XYZ under D55, and finds the spectral matrix.
  const SpectralData ssf = canon_5d2(), ill = illuminant_spd("D55");
  const SpectralData& train = idt_training_190();
  SimulationOptions so;
  so.white_level = 3000;
  const std::vector<Vec3> rgb = simulate_camera_RGB(ssf, train, ill, so);
  Vec3 white;
  const std::vector<Vec3> xyz = reflectances_to_XYZ(train, ill, Observer::CIE1931_2, &white);
  const IdtResult chart = idt_from_patches(rgb, xyz, white);
  const IdtResult spectral = idt_from_sensitivities(ssf, ill, train);
  INFO("chart\n" << chart.matrix << "\nspectral\n" << spectral.matrix);
  // The two paths differ only in their spectral sums (1 nm CMFs and the SSF grid here) and in the
  // white balance taken from a grey patch instead of the perfect diffuser.
  CHECK((chart.matrix - spectral.matrix).cwiseAbs().maxCoeff() < 0.01);
  CHECK((chart.white_balance - spectral.white_balance).cwiseAbs().maxCoeff() < 0.01);
  CHECK(chart.status == "ok");
  // The camera's value of the perfect diffuser maps to ACES (1, 1, 1): B·1 = 1 and the white balance.
  SpectralData diffuser;
  diffuser.wavelengths = {380, 780};
  diffuser.names = {"white"};
  diffuser.values = {{1.0, 1.0}};
  const Vec3 camera_white = simulate_camera_RGB(ssf, diffuser, ill, so)[0];
  INFO("ACES of the perfect diffuser " << (chart.camera_matrix() * camera_white).transpose());
  CHECK((chart.camera_matrix() * camera_white - Vec3::Ones()).cwiseAbs().maxCoeff() < 0.01);
}

TEST_CASE("idt: refusals carry codes", "[idt]") {
  const std::vector<Vec3> two = {Vec3(1, 1, 1), Vec3(0.5, 0.4, 0.3)};
  test::require_code([&] { fit_idt(two, two, Vec3::Ones()); }, ErrorCode::TooFewPatches);
  std::vector<Vec3> bad = {Vec3(1, 1, 1), Vec3(0.5, 0.4, 0.3), Vec3(NAN, 0, 0)};
  test::require_code([&] { fit_idt(bad, bad, Vec3::Ones()); }, ErrorCode::NonFinite);
  test::require_code([&] { idt_adaptation("CAT16"); }, ErrorCode::UnknownId);
  SpectralData two_channels = canon_5d2();
  two_channels.values.pop_back();
  two_channels.names.pop_back();
  test::require_code([&] { idt_from_sensitivities(two_channels, illuminant_spd("D55"), idt_training_190()); },
                           ErrorCode::InvalidArgument);
  // The only neutral patch reads negative in the camera: no white balance.
  const std::vector<Vec3> rgb = {Vec3(-1, -1, -1), Vec3(0.5, 0.4, 0.3), Vec3(0.2, 0.3, 0.4)};
  const std::vector<Vec3> ref = {Vec3(47.5, 50, 54), Vec3(40, 30, 10), Vec3(20, 30, 60)};
  test::require_code([&] { idt_from_patches(rgb, ref, Vec3(95, 100, 108)); }, ErrorCode::NegativeValue);
  test::require_code([&] { idt_from_patches(rgb, {ref[0], ref[1]}, Vec3(95, 100, 108)); }, ErrorCode::InvalidArgument);
}

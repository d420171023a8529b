// Camera quality: ISO 17321-1 SMI and the Vora–Trussell μ-factor, on planted cameras whose answer
// is known in closed form.
#include <Eigen/Dense>
#include <cmath>

#include "test_support.hpp"
#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/lab/smi.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

// The CIE 1931 CMFs on the cameras' grid (380-780 nm, 5 nm) as R, G, B sensitivities, optionally
// mixed by a 3×3 (row c = the weights of x̄, ȳ, z̄ in channel c).
SpectralData cmf_camera(const Mat3& mix = Mat3::Identity()) {
  const SpectralData a = align_spectra(cmfs(Observer::CIE1931_2), wavelength_grid(380, 780, 5));
  SpectralData s;
  s.wavelengths = a.wavelengths;
  s.names = {"R", "G", "B"};
  s.values.assign(3, std::vector<double>(a.wavelengths.size(), 0.0));
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < a.wavelengths.size(); ++i)
      for (int k = 0; k < 3; ++k) s.values[static_cast<size_t>(c)][i] += mix(c, k) * a.values[static_cast<size_t>(k)][i];
  return s;
}

double f_Lab(double t) {  // CIE 15:2004 eq 8.3
  const double e = 216.0 / 24389, k = 24389.0 / 27;
  return t > e ? std::cbrt(t) : (k * t + 16) / 116;
}

}  // namespace

TEST_CASE("lab smi: the CMFs as sensitivities (or any mix of them) score SMI 100 and mu 1", "[lab]") {
  for (const char* ill : {"D65", "A"}) {
    INFO("illuminant " << ill);
    const SpectralData L = illuminant_spd(ill);
    const CameraQuality q = camera_quality(cmf_camera(), L, "CMF");
    CHECK(q.smi == Approx(100).margin(1e-6));
    CHECK(q.mu_factor == Approx(1).margin(1e-12));
    Mat3 mix;
    mix << 0.2, 0.9, -0.05, -0.1, 1.0, 0.1, 0.02, -0.1, 0.8;
    const CameraQuality m = camera_quality(cmf_camera(mix), L, "CMF mix");
    CHECK(m.smi == Approx(100).margin(1e-6));
    CHECK(m.mu_factor == Approx(1).margin(1e-12));
    // The best-fit CMF combination reproduces such a camera's curves.
    const LutherFit fit = luther_fit(cmf_camera(mix), L);
    for (int c = 0; c < 3; ++c)
      for (size_t i = 0; i < fit.wavelengths.size(); ++i)
        CHECK(fit.fit[static_cast<size_t>(c)][i] == Approx(fit.camera[static_cast<size_t>(c)][i]).margin(1e-9));
  }
}

TEST_CASE("lab smi: a blue channel 10 % too strong under a fixed matrix scores as computed by hand", "[lab]") {
  // Camera = (x̄, ȳ, 1.1 z̄): its RGB (white's G = 1) is diag(1, 1, 1.1)·XYZ/100, so the matrix
  // 100·I gives (X, Y, 1.1 Z): L* and a* exact, Δb* = 200 (f(1.1 Z/Zw) − f(Z/Zw)) = ΔE*ab.
  Mat3 mix = Mat3::Identity();
  mix(2, 2) = 1.1;
  const SpectralData L = illuminant_spd("D65");
  const CameraQuality q = camera_quality_with_matrix(cmf_camera(mix), L, {100, 0, 0, 0, 100, 0, 0, 0, 100}, "z x 1.1");
  SpectralData refl = iso17321_reflectances();
  refl.names.resize(18);
  refl.values.resize(18);
  // XYZ summed as the SMI sums them (the virtual camera's rule with the CMFs as its curves).
  SpectralData flat = refl;
  flat.values = {std::vector<double>(refl.wavelengths.size(), 1.0)};
  flat.names = {"white"};
  const Vec3 white = simulate_camera_RGB(cmf_camera(), flat, L)[0];
  const auto XYZ = simulate_camera_RGB(cmf_camera(), refl, L);
  double sum = 0;
  for (const auto& x : XYZ) sum += 200 * std::abs(f_Lab(1.1 * x[2] / white[2]) - f_Lab(x[2] / white[2]));
  const double by_hand = 100 - 5.5 * sum / 18;
  CHECK(q.smi == Approx(by_hand).epsilon(1e-9));
  CHECK(q.smi < 95);  // a visible error: mean dE*ab above 1
  // With the matrix free, the same camera is a Luther camera again.
  CHECK(camera_quality(cmf_camera(mix), L).smi == Approx(100).margin(1e-6));
}

TEST_CASE("lab smi: a channel orthogonal to the CMFs gives mu = 2/3 exactly", "[lab]") {
  const SpectralData L = illuminant_spd("D65");
  SpectralData s = cmf_camera();
  const size_t n = s.wavelengths.size();
  const auto Lg = interpolate_spectrum(L.wavelengths, L.values[0], s.wavelengths, L.linear);
  // v: a smooth bump with its illuminant-weighted projection on the CMFs removed.
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd w(n);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) A(static_cast<Eigen::Index>(i), k) = Lg[i] * s.values[static_cast<size_t>(k)][i];
    const double x = (s.wavelengths[i] - 600) / 60;
    w(static_cast<Eigen::Index>(i)) = Lg[i] * std::exp(-x * x);
  }
  const Eigen::VectorXd u = w - A * A.colPivHouseholderQr().solve(w);
  for (size_t i = 0; i < n; ++i) s.values[2][i] = u(static_cast<Eigen::Index>(i)) / Lg[i];
  // Channels x̄, ȳ, v: trace(P_A P_S) = 2 + 0.
  CHECK(mu_factor_VoraTrussell1993(s, L) == Approx(2.0 / 3).margin(1e-10));
}

TEST_CASE("lab smi: the 52 cameras are ranked, with SMI and mu in the range real cameras reach", "[lab]") {
  const auto rows = camera_quality_ranking(illuminant_spd("D65"));
  REQUIRE(rows.size() == camera_names().size());
  for (size_t i = 0; i < rows.size(); ++i) {
    INFO(rows[i].camera << " SMI " << rows[i].smi << " mu " << rows[i].mu_factor);
    if (i > 0) CHECK(rows[i].smi <= rows[i - 1].smi);
    CHECK(rows[i].smi > 60);
    CHECK(rows[i].smi < 100);
    CHECK(rows[i].mu_factor > 0.8);
    CHECK(rows[i].mu_factor < 1);
    CHECK(rows[i].smi == Approx(100 - 5.5 * rows[i].mean_dE).margin(1e-9));
  }
}

TEST_CASE("lab smi: sensitivities without three channels are refused", "[lab]") {
  SpectralData s = cmf_camera();
  s.values.pop_back();
  s.names.pop_back();
  test::require_code([&] { camera_quality(s, illuminant_spd("D65")); }, ErrorCode::InvalidArgument);
  SpectralData z = cmf_camera();
  for (auto& v : z.values[2]) v = 0;
  test::require_code([&] { camera_quality(z, illuminant_spd("D65")); }, ErrorCode::InvalidArgument);
}

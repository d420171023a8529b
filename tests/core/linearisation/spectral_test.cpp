// Spectral characterisation (Shen et al. 2008 eqs 26-28): planted W, per-pixel = per-patch,
// CSV and JSON round trips, colorimetric error of the estimates, bad input.
#include <cmath>
#include <cstring>
#include <map>

#include "test_support.hpp"
#include "tiff_reader.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/linearisation/spectral.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

/// Reflectances in a 3-dimensional span (so W recovers them exactly), their linear camera RGB
/// through a responsivity, and stored values through the sRGB curve.
struct Planted {
  std::vector<std::string> ids;
  SpectralData reflectances;
  PatchMatrix stored;
  Linearisation lin;
};

Planted planted() {
  Planted p;
  const std::vector<double> wl = wavelength_grid(400, 700, 10);
  const size_t N = wl.size();
  Eigen::MatrixXd basis(N, 3), m(3, N);
  for (size_t i = 0; i < N; ++i) {
    const double t = (wl[i] - 400) / 300;
    basis.row(i) << 0.5, t - 0.5, std::cos(3 * t);
    m.col(i) << std::exp(-std::pow((t - 0.8) / 0.2, 2)), std::exp(-std::pow((t - 0.5) / 0.2, 2)),
        std::exp(-std::pow((t - 0.2) / 0.2, 2));
  }
  m /= (m * basis.col(0)).maxCoeff() * 2.5;  // keeps linear values below 1
  p.reflectances.wavelengths = wl;
  const int Q = 20;
  p.stored.resize(Q, 3);
  LinearisationData d;
  d.camera_RGB = PatchMatrix::Constant(1, 3, 1);
  d.full_scale = 255;
  p.lin = fit_linearisation(parse_choice("sRGB"), d);
  for (int q = 0; q < Q; ++q) {
    const Eigen::Vector3d a(1.0 + 0.03 * q, 0.2 * std::sin(q), 0.1 * std::cos(2 * q));
    const Eigen::VectorXd r = basis * a;
    p.ids.push_back("P" + std::to_string(q + 1));
    p.reflectances.names.push_back(p.ids.back());
    p.reflectances.values.emplace_back(r.data(), r.data() + N);
    const Eigen::Vector3d u = m * r;
    for (int c = 0; c < 3; ++c) p.stored(q, c) = 255 * sRGB_encode(u[c]);
  }
  return p;
}

}  // namespace

TEST_CASE("spectral: W (eq 27) recovers reflectances in a 3-dimensional span exactly", "[linearisation][spectral]") {
  const Planted p = planted();
  const SpectralModel m = fit_spectral(p.lin, p.ids, p.stored, p.reflectances);
  CHECK(m.W.rows() == 31);
  const SpectralEvaluation e = evaluate_spectral(m, p.ids, p.stored, p.reflectances, illuminant_spd("D65"));
  CHECK(e.rms_summary.max < 1e-12);
  CHECK(e.dE00_summary.max < 1e-8);
  CHECK(spectral_rms({0, 0, 0, 0}, {1, -1, 1, -1}) == 1);  // eq (28)
  // Another illuminant and observer: still exact.
  const SpectralEvaluation a = evaluate_spectral(m, p.ids, p.stored, p.reflectances, illuminant_spd("A"), Observer::CIE1964_10);
  CHECK(a.dE00_summary.max < 1e-8);
}

TEST_CASE("spectral: per-pixel estimates equal the per-patch ones, CSV and JSON round trips", "[linearisation][spectral]") {
  const Planted p = planted();
  const SpectralModel m = fit_spectral(p.lin, p.ids, p.stored, p.reflectances);
  std::vector<float> rgb;
  for (Eigen::Index q = 0; q < p.stored.rows(); ++q)
    for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<float>(p.stored(q, c)));
  std::vector<float> bands(static_cast<size_t>(p.stored.rows()) * 31);
  estimate_reflectance_image(m, rgb.data(), static_cast<size_t>(p.stored.rows()), bands.data());
  const SpectralData est = estimate_reflectances(m, p.ids, p.stored);
  double worst = 0;
  for (size_t q = 0; q < est.size(); ++q)
    for (size_t i = 0; i < 31; ++i) worst = std::max(worst, std::fabs(bands[q * 31 + i] - est.values[q][i]));
  CHECK(worst < 1e-5);  // float pixels
  // CSV: read back by the patch-file reader as a spectral table.
  const PatchTable t = read_patch_file(spectral_csv(est), "estimates.csv");
  REQUIRE(t.has_spectra);
  CHECK(t.ids == p.ids);
  for (size_t q = 0; q < est.size(); ++q)
    for (size_t i = 0; i < 31; ++i) CHECK(t.spectra.values[q][i] == Approx(est.values[q][i]).margin(1e-9));
  // JSON: exact.
  const SpectralModel back = spectral_model_from_json(json::parse(spectral_model_json(m).dump()));
  CHECK(back.W == m.W);
  CHECK(back.wavelengths == m.wavelengths);
  CHECK(back.linearisation.choice.method == "sRGB");
  json::Value bad = spectral_model_json(m);
  bad.set("format", "tristim-profile");
  test::require_code([&] { spectral_model_from_json(bad); }, ErrorCode::ProfileInvalid);
}

TEST_CASE("spectral: bad input gives coded errors", "[linearisation][spectral]") {
  const Planted p = planted();
  test::require_code([&] { fit_spectral(p.lin, {"P1", "P2"}, p.stored.topRows(2), p.reflectances); }, ErrorCode::TooFewPatches);
  test::require_code([&] { fit_spectral(p.lin, {"P1", "P2"}, p.stored, p.reflectances); }, ErrorCode::PatchMismatch);
  std::vector<std::string> ids = p.ids;
  ids[3] = "Q9";
  test::require_code([&] { fit_spectral(p.lin, ids, p.stored, p.reflectances); }, ErrorCode::MissingColumn);
  PatchMatrix flat = p.stored;
  flat.col(2) = flat.col(1);
  test::require_code([&] { fit_spectral(p.lin, p.ids, flat, p.reflectances); }, ErrorCode::IllConditioned);
}

TEST_CASE("spectral: the multi-band float TIFF holds every band", "[linearisation][spectral]") {
  const int w = 3, h = 2, bands = 31;
  std::vector<float> px(static_cast<size_t>(w * h * bands));
  for (size_t i = 0; i < px.size(); ++i) px[i] = 0.01f * static_cast<float>(i);
  const std::vector<uint8_t> b = float_tiff_bands(px.data(), w, h, bands, "reflectance");
  auto tags = test::tiff_tags(b);
  using V = std::vector<uint32_t>;
  CHECK(tags[277].values == V{bands});                        // SamplesPerPixel
  CHECK(tags[262].values == V{1});                            // MinIsBlack
  CHECK(tags[338].values == V(bands - 1, 0));                 // ExtraSamples: unspecified
  CHECK(tags[258].values == V(bands, 32));                    // BitsPerSample
  CHECK(tags[339].values == V(bands, 3));                     // SampleFormat: float, every band
  CHECK(tags[270].ascii == "reflectance");
  CHECK(test::tiff_float_strip(b) == px);                     // every band of every pixel, verbatim
}

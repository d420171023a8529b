// Spectral characterisation (Shen et al. 2008 eqs 26-28): planted W, per-pixel = per-patch,
// CSV and JSON round trips, colorimetric error of the estimates, bad input.
#include <Eigen/LU>
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
  std::vector<std::string> ids, greys;
  SpectralData reflectances;
  PatchMatrix stored;
  Linearisation lin;
  Eigen::MatrixXd W;  // N × 3, the planted map (planted_with_greys)

  /// Adds patch `id`: reflectance r, linear camera RGB u, stored as 255 · sRGB_encode(u).
  void add(const std::string& id, const Eigen::VectorXd& r, const Eigen::Vector3d& u) {
    ids.push_back(id);
    reflectances.names.push_back(id);
    reflectances.values.emplace_back(r.data(), r.data() + r.size());
    stored.conservativeResize(stored.rows() + 1, 3);
    for (int c = 0; c < 3; ++c) stored(stored.rows() - 1, c) = 255 * sRGB_encode(u[c]);
  }
};

/// A 3-dimensional reflectance span `basis` (N × 3, its first column flat) on 400-700 nm at 10 nm
/// and a camera's responsivities m (3 × N, Gaussian R, G, B), scaled to keep linear values below 1.
struct SpanCamera {
  std::vector<double> wl;
  Eigen::MatrixXd basis, m;
};

SpanCamera span_camera() {
  SpanCamera s;
  s.wl = wavelength_grid(400, 700, 10);
  const size_t N = s.wl.size();
  s.basis.resize(N, 3);
  s.m.resize(3, N);
  for (size_t i = 0; i < N; ++i) {
    const double t = (s.wl[i] - 400) / 300;
    s.basis.row(i) << 0.5, t - 0.5, std::cos(3 * t);
    s.m.col(i) << std::exp(-std::pow((t - 0.8) / 0.2, 2)), std::exp(-std::pow((t - 0.5) / 0.2, 2)),
        std::exp(-std::pow((t - 0.2) / 0.2, 2));
  }
  s.m /= (s.m * s.basis.col(0)).maxCoeff() * 2.5;
  return s;
}

/// No patches yet, on the span camera's wavelengths; the linearisation is the sRGB curve.
Planted start_planted(const SpanCamera& s) {
  Planted p;
  p.reflectances.wavelengths = s.wl;
  LinearisationData d;
  d.camera_RGB = PatchMatrix::Constant(1, 3, 1);
  d.full_scale = 255;
  p.lin = fit_linearisation(parse_choice("sRGB"), d);
  return p;
}

Planted planted() {
  const SpanCamera s = span_camera();
  Planted p = start_planted(s);
  for (int q = 0; q < 20; ++q) {
    const Eigen::VectorXd r = s.basis * Eigen::Vector3d(1.0 + 0.03 * q, 0.2 * std::sin(q), 0.1 * std::cos(2 * q));
    p.add("P" + std::to_string(q + 1), r, s.m * r);
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

namespace {

/// A camera with known sensitivities m (3 × N) and reflectances in a 3-dimensional span B, so
/// the planted spectral map is W = B (m B)⁻¹ (r = W u for every reflectance of the span). Six
/// spectrally flat greys (in the span too) are photographed with flare (u·1.1 + 0.03), so they
/// do not follow the map: W trained on the non-grey patches must still be the planted one.
Planted planted_with_greys() {
  const SpanCamera s = span_camera();
  const Eigen::MatrixXd &B = s.basis, &m = s.m;
  Planted p = start_planted(s);
  p.W = B * (m * B).inverse();
  for (int q = 0; q < 18; ++q) {  // chromatic: clearly away from the neutral axis
    const Eigen::VectorXd r = B * Eigen::Vector3d(1.0 + 0.03 * q, (q % 2 ? 1 : -1) * (0.3 + 0.3 * std::fabs(std::sin(q))), 0.3 * std::cos(2 * q));
    p.add("C" + std::to_string(q + 1), r, m * r);
  }
  for (int g = 0; g < 6; ++g) {
    const Eigen::VectorXd r = B.col(0) * (0.15 + 0.3 * g);  // flat reflectance 0.075 .. 0.825
    Eigen::Vector3d u = m * r;
    u = (u * 1.1).array() + 0.03;  // flare
    p.greys.push_back("G" + std::to_string(g + 1));
    p.add(p.greys.back(), r, u);
  }
  return p;
}

}  // namespace

TEST_CASE("spectral: W trained on the non-grey patches (the paper's default) recovers the planted map", "[linearisation][spectral]") {
  const Planted p = planted_with_greys();
  const SpectralModel m = fit_spectral(p.lin, p.ids, p.stored, p.reflectances);
  CHECK(m.training_set == "non-grey");
  CHECK(m.greys == p.greys);  // the flat ones, found by the Shen2008 linearisation's rule
  CHECK(m.training_patches == 18);
  CHECK(m.training_ids == std::vector<std::string>(p.ids.begin(), p.ids.begin() + 18));
  const double scale = p.W.cwiseAbs().maxCoeff();
  INFO("worst |W - W_planted| " << (m.W - p.W).cwiseAbs().maxCoeff() << " of " << scale);
  CHECK((m.W - p.W).cwiseAbs().maxCoeff() < 1e-9 * scale);
  // Every option of the catalog row is accepted by name; use_greys = 1 trains on all 24, and the
  // flared greys pull W off the planted map.
  const SpectralModel all = fit_spectral(p.lin, p.ids, p.stored, p.reflectances, MethodChoice{"", {{"use_greys", 1}}, {}});
  CHECK(all.training_set == "all");
  CHECK(all.training_patches == 24);
  CHECK((all.W - p.W).cwiseAbs().maxCoeff() > 1e-3 * scale);
  // Given greys: only those are left out.
  const SpectralModel given = fit_spectral(p.lin, p.ids, p.stored, p.reflectances, MethodChoice{"", {}, {{"grey", "G1;G2"}}});
  CHECK(given.training_patches == 22);
  CHECK(given.greys == std::vector<std::string>{"G1", "G2"});
}

TEST_CASE("spectral: the non-grey default changes the training set and nothing else", "[linearisation][spectral]") {
  // The default equals use_greys = 1 on the non-grey rows alone, bit for bit: the same W, the same
  // estimates for every patch (greys included); only the training set differs.
  const Planted p = planted_with_greys();
  const SpectralModel def = fit_spectral(p.lin, p.ids, p.stored, p.reflectances);
  const std::vector<std::string> chromatic(p.ids.begin(), p.ids.begin() + 18);
  const SpectralModel sub =
      fit_spectral(p.lin, chromatic, p.stored.topRows(18), p.reflectances, MethodChoice{"", {{"use_greys", 1}}, {}});
  CHECK(def.W == sub.W);
  CHECK(def.wavelengths == sub.wavelengths);
  CHECK(estimate_reflectances(def, p.ids, p.stored).values == estimate_reflectances(sub, p.ids, p.stored).values);
  // With no greys among the patches the default trains on all of them, as before.
  const SpectralModel none = fit_spectral(p.lin, chromatic, p.stored.topRows(18), p.reflectances);
  CHECK(none.training_set == "non-grey");
  CHECK(none.greys.empty());
  REQUIRE(none.training_patches == 18);
  CHECK(none.W == sub.W);
  // JSON: the training set round-trips; a model written before it existed was trained on all.
  const SpectralModel back = spectral_model_from_json(json::parse(spectral_model_json(def).dump()));
  CHECK(back.training_set == "non-grey");
  CHECK(back.training_ids == def.training_ids);
  CHECK(back.greys == def.greys);
  CHECK(back.grey_reason == def.grey_reason);
  json::Value old = json::Value::object();
  const json::Value current = spectral_model_json(def);
  for (const auto& [k, v] : current.members())
    if (k != "training_set" && k != "training_ids" && k != "greys" && k != "grey_reason") old.set(k, v);
  CHECK(spectral_model_from_json(old).training_set == "all");
  json::Value bad = spectral_model_json(def);
  bad.set("training_set", "greys");
  test::require_code([&] { spectral_model_from_json(bad); }, ErrorCode::ProfileInvalid);
  // Bad options and too few non-grey patches: coded errors.
  test::require_code([&] { fit_spectral(p.lin, p.ids, p.stored, p.reflectances, MethodChoice{"", {{"J", 3}}, {}}); },
                     ErrorCode::UnknownId);
  test::require_code([&] { fit_spectral(p.lin, p.ids, p.stored, p.reflectances, MethodChoice{"", {}, {{"grey", "Z9"}}}); },
                     ErrorCode::UnknownId);
  const std::vector<std::string> greys_only(p.ids.begin() + 18, p.ids.end());
  test::require_code([&] { fit_spectral(p.lin, greys_only, p.stored.bottomRows(6), p.reflectances); }, ErrorCode::TooFewPatches);
}

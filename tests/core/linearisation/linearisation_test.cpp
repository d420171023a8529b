// The linearisation table: fixed curves, grey- and colour-based polynomials, grey choice,
// inverses, JSON round trip and bad input.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "detmath.hpp"
#include "test_support.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/linearisation/guarnera2018.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/linearisation/spectral.hpp"

using namespace tristim;

namespace {

LinearisationData chart_data(const std::string& chart, const PatchMatrix& rgb) {
  const ReferenceChart ref = reference_chart(chart, "D65");
  LinearisationData d;
  d.ids = ref.ids;
  d.camera_RGB = rgb;
  d.reference_XYZ.resize(static_cast<Eigen::Index>(ref.XYZ.size()), 3);
  for (size_t i = 0; i < ref.XYZ.size(); ++i) d.reference_XYZ.row(static_cast<Eigen::Index>(i)) = ref.XYZ[i].transpose();
  d.white = ref.white;
  return d;
}

}  // namespace

TEST_CASE("linearisation table: ids in the issue's order, options complete, choice syntax", "[linearisation]") {
  std::vector<std::string> ids;
  for (const auto& m : linearisation_table()) ids.push_back(m.info.id);
  const std::vector<std::string> expected{"identity", "gamma", "sRGB", "grey-polynomial", "grey-log-polynomial",
                                          "colour-polynomial", "colour-log-polynomial", "Guarnera2018", "Shen2008"};
  CHECK(ids == expected);
  const MethodChoice c = complete_choice(linearisation_method("Shen2008").info, parse_choice("Shen2008:J=6,grey=D1;D2;D3"));
  CHECK(choice_number(c, "J") == 6);
  CHECK(choice_number(c, "K") == 2);
  CHECK(choice_number(c, "L") == 2);
  CHECK(choice_text(c, "basis") == "munsell1269");
  CHECK(choice_text(c, "grey") == "D1;D2;D3");
  CHECK(choice_number(complete_choice(linearisation_method("gamma").info, parse_choice("gamma")), "gamma") == 2.2);
  test::require_code([] { linearisation_method("Guarnera2019"); }, ErrorCode::UnknownId);
  test::require_code([] { complete_choice(linearisation_method("Shen2008").info, parse_choice("Shen2008:J=0")); },
                     ErrorCode::InvalidArgument);
  test::require_code([] { complete_choice(linearisation_method("gamma").info, parse_choice("gamma:K=2")); },
                     ErrorCode::UnknownId);
}

TEST_CASE("linearisation: gamma and sRGB are exact and invert on a grid (1e-12)", "[linearisation]") {
  LinearisationData d;
  d.camera_RGB = PatchMatrix::Constant(1, 3, 100);
  d.full_scale = 255;
  for (const char* id : {"identity", "gamma", "sRGB"}) {
    const Linearisation l = fit_linearisation(parse_choice(id), d);
    const LinearisationMethod& m = linearisation_method(id);
    for (int i = 0; i <= 255; ++i)
      for (int c = 0; c < 3; ++c) {
        const double y = m.apply(l, c, i);
        CHECK(std::fabs(m.inverse(l, c, y) - i) <= 1e-12 * 255);
      }
  }
  const Linearisation g = fit_linearisation(parse_choice("gamma:gamma=2.2"), d);
  CHECK(linearisation_method("gamma").apply(g, 0, 127.5) == Approx(std::pow(0.5, 2.2)).epsilon(1e-15));
  const Linearisation s = fit_linearisation(parse_choice("sRGB"), d);
  CHECK(linearisation_method("sRGB").apply(s, 1, 255 * 0.04045) == Approx(0.04045 / 12.92).epsilon(1e-14));
  CHECK(linearisation_method("sRGB").apply(s, 1, 255) == Approx(1).epsilon(1e-15));
}

TEST_CASE("linearisation: polyfit recovers a planted polynomial, R² and correlation", "[linearisation]") {
  const std::vector<double> c{0.02, 0.3, -0.1, 0.9};
  std::vector<double> x, y;
  for (int i = 0; i < 12; ++i) {
    x.push_back(0.05 + 0.08 * i);
    y.push_back(polyval(c, x.back()));
  }
  const std::vector<double> f = polyfit(x, y, 3);
  for (int k = 0; k < 4; ++k) CHECK(f[k] == Approx(c[k]).margin(1e-12));
  CHECK(coefficient_of_determination(y, y) == 1);
  std::vector<double> z;
  for (double v : y) z.push_back(3 * v + 1);
  CHECK(squared_correlation(y, z) == Approx(1).epsilon(1e-14));
  test::require_code([&] { polyfit({0.1, 0.2}, {1, 2}, 2); }, ErrorCode::TooFewPatches);
  test::require_code([&] { polyfit({0.2, 0.2, 0.2}, {1, 2, 3}, 2); }, ErrorCode::IllConditioned);
}

TEST_CASE("linearisation: automatic greys on the ColorChecker say which and why", "[linearisation]") {
  const ReferenceChart ref = reference_chart("cc24", "D65");
  LinearisationData d = chart_data("cc24", PatchMatrix::Ones(24, 3));
  const GreySelection g = select_greys(d, {}, 2.0);
  std::vector<std::string> greys;
  for (int r : g.rows) greys.push_back(d.ids[r]);
  // The post-2014 white D1 is more than 2 ΔE00 from neutral under D65; D2..D6 are greys.
  CHECK(greys == std::vector<std::string>{"D2", "D3", "D4", "D5", "D6"});
  CHECK(g.reason.find("automatic") != std::string::npos);
  CHECK(g.reason.find("D6 0.") != std::string::npos);
  const GreySelection given = select_greys(d, split_ids("D1;D2,D3"), 2.0);
  CHECK(given.rows == std::vector<int>{18, 19, 20});
  test::require_code([&] { select_greys(d, {"Z9"}, 2.0); }, ErrorCode::UnknownId);
  LinearisationData bare;
  bare.ids = d.ids;
  bare.camera_RGB = d.camera_RGB;
  test::require_code([&] { select_greys(bare, {}, 2.0); }, ErrorCode::MissingColumn);
}

TEST_CASE("linearisation: grey and colour polynomials recover a planted per-channel OECF", "[linearisation]") {
  // Stored values ρ_c = 255 · F_c(t_c) with F_c the inverse of a cubic (different per channel);
  // t = the greys' Y / Y_white (grey rows) or the linear sRGB of the reference (colour rows).
  const ReferenceChart ref = reference_chart("cc24", "D65");
  const std::vector<std::vector<double>> cubic{{0.0, 0.6, 0.1, 0.3}, {0.01, 0.5, 0.3, 0.2}, {0.0, 0.8, -0.1, 0.3}};
  LinearisationData d = chart_data("cc24", PatchMatrix::Zero(24, 3));
  d.full_scale = 255;
  const Mat3 M = display_matrix(ref.white);
  for (const bool grey : {true, false}) {
    for (Eigen::Index i = 0; i < 24; ++i) {
      const Vec3 t = grey ? Vec3::Constant(ref.XYZ[i][1] / ref.white[1]) : Vec3(M * ref.XYZ[i]);
      for (int c = 0; c < 3; ++c) {
        // invert the cubic by bisection on [0, 1.2]: x with P(x) = t
        double lo = 0, hi = 1.2;
        for (int it = 0; it < 200; ++it) (polyval(cubic[c], 0.5 * (lo + hi)) < t[c] ? lo : hi) = 0.5 * (lo + hi);
        // out of the curve's range (a colour outside the sRGB gamut): stored as 0, clipped
        d.camera_RGB(i, c) = t[c] <= polyval(cubic[c], 0) ? 0 : 255 * 0.5 * (lo + hi);
      }
    }
    const std::string id = grey ? "grey-polynomial" : "colour-polynomial";
    MethodChoice choice = parse_choice(id + ":K=3");
    if (grey) choice.settings["grey"] = "D1;D2;D3;D4;D5;D6";
    const Linearisation l = fit_linearisation(choice, d);
    INFO(id << ": " << l.message);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 4; ++k) CHECK(l.coefficients[c][k] == Approx(cubic[c][k]).margin(1e-8));
      CHECK(l.r_squared[c] == Approx(1).margin(1e-12));
    }
    CHECK(l.monotonic);
    if (grey) CHECK(l.greys.size() == 6);
    CHECK(l.grey_reason == (grey ? "given: 6 patches" : ""));
    // apply ∘ inverse on the patches
    const PatchMatrix lin = linearise(l, d.camera_RGB);
    const PatchMatrix back = delinearise(l, lin);
    CHECK((back - d.camera_RGB).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("linearisation: log-polynomials fit a power law exactly, clipped patches are named", "[linearisation]") {
  const ReferenceChart ref = reference_chart("cc24", "D65");
  LinearisationData d = chart_data("cc24", PatchMatrix::Zero(24, 3));
  d.full_scale = 255;
  for (Eigen::Index i = 0; i < 24; ++i)
    for (int c = 0; c < 3; ++c) d.camera_RGB(i, c) = 255 * std::pow(ref.XYZ[i][1] / ref.white[1] * 0.95, 1 / 2.2);
  d.camera_RGB(18, 0) = 255;  // D1 red clipped
  MethodChoice choice = parse_choice("grey-log-polynomial:K=1");
  choice.settings["grey"] = "D1;D2;D3;D4;D5;D6";
  const Linearisation l = fit_linearisation(choice, d);
  CHECK(l.message.find("channel R: clipped (0 or full scale) and left out: D1") != std::string::npos);
  for (int c = 0; c < 3; ++c) {
    CHECK(l.coefficients[c][1] == Approx(2.2).epsilon(1e-12));                // ln y = ln 0.95⁻¹·… + 2.2 ln x
    CHECK(l.coefficients[c][0] == Approx(-std::log(0.95)).margin(1e-12));
  }
  const LinearisationMethod& m = linearisation_method("grey-log-polynomial");
  CHECK(m.apply(l, 1, 0) == 0);
  CHECK(m.inverse(l, 2, m.apply(l, 2, 77)) == Approx(77).epsilon(1e-12));
}

TEST_CASE("linearisation: a non-monotonic curve is flagged, not hidden", "[linearisation]") {
  LinearisationData d = chart_data("cc24", PatchMatrix::Zero(24, 3));
  d.full_scale = 255;
  // Stored values that fall as Y rises over the top greys: a degree-2 fit bends down.
  const double stored[6] = {150, 250, 240, 120, 60, 20};
  for (int i = 0; i < 6; ++i) d.camera_RGB.row(18 + i).setConstant(stored[i]);
  MethodChoice choice = parse_choice("grey-polynomial:K=2");
  choice.settings["grey"] = "D1;D2;D3;D4;D5;D6";
  const Linearisation l = fit_linearisation(choice, d);
  CHECK_FALSE(l.monotonic);
  CHECK(l.message.find("not increasing") != std::string::npos);
}

TEST_CASE("linearisation: bad input gives coded errors", "[linearisation]") {
  LinearisationData d = chart_data("cc24", PatchMatrix::Constant(24, 3, 100));
  d.full_scale = 255;
  MethodChoice few = parse_choice("grey-polynomial:K=3");
  few.settings["grey"] = "D2;D3;D4";
  test::require_code([&] { fit_linearisation(few, d); }, ErrorCode::TooFewPatches);
  LinearisationData bad = d;
  bad.camera_RGB(3, 1) = std::nan("");
  test::require_code([&] { fit_linearisation(parse_choice("gamma"), bad); }, ErrorCode::NonFinite);
  LinearisationData mismatch = d;
  mismatch.ids.pop_back();
  test::require_code([&] { fit_linearisation(parse_choice("sRGB"), mismatch); }, ErrorCode::PatchMismatch);
  LinearisationData clipped = d;
  clipped.camera_RGB.setConstant(255);
  MethodChoice all = parse_choice("grey-polynomial");
  all.settings["grey"] = "D1;D2;D3;D4;D5;D6";
  test::require_code([&] { fit_linearisation(all, clipped); }, ErrorCode::NoUsableData);
  LinearisationData none;
  none.camera_RGB = d.camera_RGB;
  test::require_code([&] { fit_linearisation(parse_choice("colour-polynomial"), none); }, ErrorCode::MissingColumn);
  test::require_code([&] { fit_linearisation(parse_choice("Shen2008"), d); }, ErrorCode::MissingColumn);
}

TEST_CASE("linearisation: JSON round trip is exact", "[linearisation]") {
  const ReferenceChart ref = reference_chart("cc24", "D65");
  LinearisationData d = chart_data("cc24", PatchMatrix::Zero(24, 3));
  d.full_scale = 255;
  for (Eigen::Index i = 0; i < 24; ++i)
    d.camera_RGB.row(i) = (255 * (display_matrix(ref.white) * ref.XYZ[i]).cwiseMax(0.001).array().pow(1 / 2.1)).matrix().transpose();
  const Linearisation l = fit_linearisation(parse_choice("colour-polynomial:K=2"), d);
  const Linearisation back = linearisation_from_json(json::parse(linearisation_json(l).dump()));
  CHECK(back.choice.method == l.choice.method);
  CHECK(back.choice.parameters == l.choice.parameters);
  CHECK(back.coefficients == l.coefficients);
  CHECK(back.domain == l.domain);
  CHECK(back.fitted == l.fitted);
  CHECK((linearise(back, d.camera_RGB) - linearise(l, d.camera_RGB)).cwiseAbs().maxCoeff() == 0);
  json::Value broken = linearisation_json(l);
  broken.set("coefficients", json::Value::array());
  test::require_code([&] { linearisation_from_json(broken); }, ErrorCode::ProfileInvalid);
  json::Value unknown = linearisation_json(l);
  unknown.set("method", "cubic-spline");
  test::require_code([&] { linearisation_from_json(unknown); }, ErrorCode::UnknownId);
}

TEST_CASE("linearisations give the same bits natively and in wasm (pinned hashes)", "[linearisation][cross-build]") {
  // Power laws, log-polynomials and Guarnera's eq (8) use detmath's pow, exp and log (detmath.hpp),
  // not the C library's, which round differently natively (glibc) and in wasm (musl): pow in
  // 0.14 % of 300,000 draws, log 0.02 %, exp 0.07 % — enough for the BOBYQA fit of
  // eq (8) below to take other steps (with the C library's: 110 evaluations natively, 109 in wasm,
  // other coefficients). The same hashes are expected in both builds; re-pin both after a
  // change that moves a bit. Data: the cc24 chart with a power-law camera and 1 % of
  // multiplicative ripple from mt19937's integers (the same draws in both builds).
  const ReferenceChart ref = reference_chart("cc24", "D65");
  LinearisationData d = chart_data("cc24", PatchMatrix::Zero(24, 3));
  d.full_scale = 255;
  std::mt19937 rng(21);
  auto ripple = [&] { return 1.0 + 0.01 * ((static_cast<double>(rng()) + 0.5) / 4294967296.0 - 0.5); };
  const double gamma[3] = {1 / 2.2, 1 / 2.0, 1 / 2.4};
  for (Eigen::Index i = 0; i < 24; ++i)
    for (int c = 0; c < 3; ++c) d.camera_RGB(i, c) = 255 * std::sqrt(ref.XYZ[i][c] / ref.white[c] * 0.9) * ripple();
  for (Eigen::Index i = 0; i < 24; ++i)  // the power from std::pow would differ: through detmath
    for (int c = 0; c < 3; ++c) d.camera_RGB(i, c) = 255 * tristim::detmath::pow(d.camera_RGB(i, c) / 255, 2 * gamma[c]);
  struct Case {
    const char* choice;
    std::uint64_t hash;
  };
  const Case cases[] = {
      {"gamma:gamma=2.2", 0xdc69079a79b902b9ULL},
      {"sRGB", 0x187359abf1802ac9ULL},
      {"grey-log-polynomial:K=2", 0x31ad17551cf67151ULL},
      {"colour-log-polynomial:K=2", 0x809b82de39444064ULL},
  };
  for (const Case& c : cases) {
    MethodChoice choice = parse_choice(c.choice);
    if (std::string(c.choice).rfind("grey", 0) == 0) choice.settings["grey"] = "D1;D2;D3;D4;D5;D6";
    const Linearisation l = fit_linearisation(choice, d);
    test::BitHash h;
    for (const auto& k : l.coefficients)
      for (double v : k) h.add(v);
    const PatchMatrix lin = linearise(l, d.camera_RGB), back = delinearise(l, lin);
    for (Eigen::Index i = 0; i < lin.size(); ++i) {
      h.add(lin.data()[i]);
      h.add(back.data()[i]);
    }
    INFO(c.choice << ": hash " << h.text());
    CHECK(h.value == c.hash);
  }
  // Guarnera's eq (8) by BOBYQA over detmath's pow (the luminance chain's linearisation).
  const InverseOecf truth{0.002, 3.7, 1.06};
  std::vector<OecfSample> s;
  for (double eps : {0.5, 1.0, 2.0, 4.0})
    for (double Y = 5; Y <= 200; Y += 15) s.push_back({truth.forward(Y * eps) * ripple(), eps, Y});
  const OecfFit f = fit_inverse_oecf_Guarnera2018(s);
  test::BitHash h;
  for (double v : {f.curve.k1, f.curve.k2, f.curve.k3, f.rms_relative}) h.add(v);
  INFO("Guarnera2018 eq (8): " << f.evaluations << " evaluations, hash " << h.text());
  CHECK(h.value == 0xec9aa6137d64837cULL);
}

TEST_CASE("linearise_image: whole-number samples from a table — the same floats as a call per sample", "[linearisation]") {
  // linearise_image keeps a per-channel table for samples that are whole numbers 0..65535 (8- and
  // 16-bit images); every other sample (fractions, negatives, −0, beyond 65535, NaN) is computed.
  std::vector<float> img;
  for (int v = 0; v < 300; ++v) img.push_back(static_cast<float>(v));  // 8-bit values, some repeated below
  for (float v : {0.5f, 254.75f, -3.0f, -0.0f, 65535.0f, 65536.0f, 70000.5f, 1e9f, 12.0f, 12.0f, 299.0f})
    img.push_back(v);
  // Near the whole-number test's edges: halves (x + 2^23 rounds them to even), the largest float
  // below 65535 and a whole number just past it, subnormals, ∞, NaN, 2^23.
  for (float v : {65534.5f, 32767.5f, 1.5f, 2.5f, std::nextafter(65535.0f, 0.0f), 65537.0f,
                  std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                  std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(), 8388608.0f, 1.0f})
    img.push_back(v);
  while (img.size() % 3) img.push_back(7.0f);
  LinearisationData none;
  none.camera_RGB = PatchMatrix::Constant(1, 3, 100);
  none.full_scale = 255;
  for (const char* id : {"gamma", "sRGB"}) {
    Linearisation l = fit_linearisation(parse_choice(id), none);
    if (std::string(id) == "gamma") l.coefficients = {std::vector<double>{2.2}, {1.8}, {2.4}};  // one table per channel
    const LinearisationMethod& m = linearisation_method(id);
    std::vector<float> out = img;
    linearise_image(l, out.data(), out.size() / 3);
    // In pieces through one ImageLineariser (its tables kept between calls): the same floats.
    std::vector<float> pieces = img;
    ImageLineariser lineariser(l);
    for (size_t at = 0, step = 1; at < pieces.size() / 3; at += step, step = step * 2 + 1)
      lineariser.apply(pieces.data() + 3 * at, std::min(step, pieces.size() / 3 - at));
    CHECK(std::memcmp(pieces.data(), out.data(), out.size() * sizeof(float)) == 0);
    for (size_t i = 0; i < img.size(); ++i) {
      const float want = static_cast<float>(m.apply(l, static_cast<int>(i % 3), img[i]));
      INFO(id << ": sample " << i << " = " << img[i] << " -> " << out[i] << ", per sample " << want);
      std::uint32_t a, b;
      std::memcpy(&a, &out[i], 4);
      std::memcpy(&b, &want, 4);
      CHECK(a == b);
    }
  }
}

TEST_CASE("catalog: every row's need has its words for the pickers", "[linearisation][catalog]") {
  for (const auto& m : linearisation_table()) {
    INFO(m.info.id);
    CHECK(!linearisation_needs_text(m.needs).empty());
  }
  CHECK(linearisation_needs_text("reference") == "fitted against the reference XYZ of every patch");
  tristim::test::require_code([] { linearisation_needs_text("nothing"); }, ErrorCode::UnknownId);
}

TEST_CASE("linearisation fields: documents of b19940b read back and write the same bytes, unknown members refused",
          "[linearisation][spectral][fields]") {
  // Written by the hand-written writers before the field lists (tests/data/documents/SOURCES.md):
  // a spectral model with its Shen2008 linearisation and the training errors beside it.
  const json::Value doc = json::parse(test::read_test_file("tests/data/documents/spectral_model_v1.json"));
  const SpectralModel m = spectral_model_from_json(doc);  // "training": known, not read
  json::Value model = json::Value::object();
  for (const auto& [k, v] : doc.members())
    if (k != "training") model.set(k, v);
  CHECK(spectral_model_json(m).dump(2) == model.dump(2));
  const Linearisation& l = m.linearisation;
  REQUIRE(l.choice.method == "Shen2008");
  REQUIRE(!l.extrapolated.empty());
  // The training errors are a SpectralEvaluation's list: read and written back the same.
  SpectralEvaluation e;
  fields::read(*doc.find("training"), e, fields::Context{});
  CHECK(e.ids.size() == 24);
  CHECK(fields::write(e).dump(2) == doc.find("training")->dump(2));
  // A linearisation as a profile of b19940b embeds it (tristim fit --linearisation gamma:gamma=1.8): R² null.
  const json::Value gamma = json::parse(
      R"({"method": "gamma", "parameters": {"gamma": 1.8}, "settings": {}, "full_scale": 238, "coefficients": [[1.8], [1.8], [1.8]], )"
      R"("domain": [[0, 1], [0, 1], [0, 1]], "r_squared": [null, null, null], "fitted": [], "greys": [], "grey_reason": "", )"
      R"("grey_coefficients": [[], [], []], "monotonic": true, "message": ""})");
  const Linearisation g = linearisation_from_json(gamma);
  CHECK(std::isnan(g.r_squared[1]));
  CHECK(linearisation_json(g).dump() == gamma.dump());

  // Written by the list, read back equal: every member, as what it writes again (17 digits: exact).
  const Linearisation back = linearisation_from_json(json::parse(linearisation_json(l).dump()));
  CHECK(linearisation_json(back).dump() == linearisation_json(l).dump());
  CHECK(back.r_squared == l.r_squared);
  REQUIRE(back.extrapolated.size() == l.extrapolated.size());
  CHECK(back.extrapolated.back().relative == l.extrapolated.back().relative);
  const SpectralModel m2 = spectral_model_from_json(json::parse(spectral_model_json(m).dump()));
  CHECK(m2.W == m.W);
  CHECK(m2.training_ids == m.training_ids);
  // Curve samples: the CLI's curves; grey_based only where there is one.
  const CurveSamples s = sample_curve(l, 1, 5), sg = sample_curve(g, 1, 5);
  CurveSamples s2, sg2;
  fields::read(fields::write(s), s2, fields::Context{});
  fields::read(fields::write(sg), sg2, fields::Context{});
  CHECK(s2.x == s.x);
  CHECK(s2.linear == s.linear);
  CHECK(s2.grey_based == s.grey_based);
  CHECK(s.grey_based.size() == 5);
  CHECK(fields::write(sg).find("grey_based") == nullptr);
  CHECK(sg2.linear == sg.linear);

  // Unknown members refused, in the model and in its linearisation; another version; a curve without coefficients.
  const auto with = [](json::Value o, const char* key, json::Value v) {
    o.set(key, std::move(v));
    return o;
  };
  test::require_code([&] { spectral_model_from_json(with(model, "spline", 1)); }, ErrorCode::ProfileInvalid);
  test::require_code([&] { spectral_model_from_json(with(model, "linearisation", with(*model.find("linearisation"), "spline", 1))); },
                     ErrorCode::ProfileInvalid);
  test::require_code([&] { spectral_model_from_json(with(model, "version", 2)); }, ErrorCode::ProfileVersion);
  test::require_code([&] { spectral_model_from_json(with(model, "W", json::Value::array())); }, ErrorCode::ProfileInvalid);
  test::require_code([&] { linearisation_from_json(with(gamma, "spline", 1)); }, ErrorCode::ProfileInvalid);
  test::require_code([&] { linearisation_from_json(with(gamma, "coefficients", json::parse("[[], [], []]"))); },
                     ErrorCode::ProfileInvalid);
  json::Value missing = json::Value::object();
  for (const auto& [k, v] : gamma.members())
    if (k != "monotonic") missing.set(k, v);
  test::require_code([&] { linearisation_from_json(missing); }, ErrorCode::ProfileInvalid);
}

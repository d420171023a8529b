// Phase I surface fits: planted coefficients recovered, coded bad input, and the real
// ColorChecker SG measured in two geometries (the paper's ranking of the corrections).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "test_support.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/surface/fit.hpp"
#include "tristim/surface/saunderson.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;

namespace {

// The built-in SG spectra (core/data: X-Rite before Nov 2014, as dcamprof redistributes them), 400-700 nm.
SpectralData sg_before() {
  return read_spectral_csv(test::read_test_file("core/data/charts/colorcheckerSG_before_nov2014_reflectance_380-730_10nm.csv"),
                           "dcamprof SG before 2014");
}
SpectralData sg_sci() {
  return read_spectral_csv(test::read_test_file("examples/web/sg_d8_sci_coolpi.csv"), "coolpi XRCCSG");
}

// `d` corrected by `choice`, column names as given.
SpectralData planted(const SpectralData& d, const std::string& choice) {
  return correct_surface(parse_choice(choice), d);
}

}  // namespace

TEST_CASE("Phase I recovers planted coefficients", "[surface][fit]") {
  const SpectralData base = sg_before();
  SECTION("scaler, offset, scaler-offset") {
    for (const char* text : {"scaler:mu=0.93", "offset:rho=0.021", "scaler-offset:mu=0.93,rho=0.035"}) {
      const MethodChoice truth = complete_choice(surface_method(parse_choice(text).method).info, parse_choice(text));
      const SurfaceFitResult r = fit_surface({truth.method, {}, {}}, base, planted(base, text));
      INFO(text << " -> " << surface_choice_text(r.choice));
      for (const auto& [name, value] : truth.parameters) CHECK(r.choice.parameters.at(name) == Approx(value).margin(1e-7));
      CHECK(r.spectral_rms_after < 1e-8);
      CHECK(r.summary_dE00_after.max < 1e-5);
    }
  }
  SECTION("saunderson, capture coefficients free (instrument fixed to the truth)") {
    const std::string text = "saunderson:k1=0.04,k2=0.6,k_ins=0,k1_capture=0.07,k2_capture=0.45,k_ins_capture=0.4";
    MethodChoice start = parse_choice("saunderson:k1=0.04,k2=0.6,k_ins=0,k1_capture=0.092,k2_capture=0.6,k_ins_capture=1");
    const SpectralData target = planted(base, text);
    const SurfaceFitResult r = fit_surface(start, base, target);
    INFO(surface_choice_text(r.choice) << " rms " << r.spectral_rms_after);
    CHECK(r.spectral_rms_after < 1e-7);
    CHECK(r.choice.parameters.at("k1_capture") == Approx(0.07).margin(1e-4));
    CHECK(r.choice.parameters.at("k2_capture") == Approx(0.45).margin(1e-4));
    CHECK(r.choice.parameters.at("k_ins_capture") == Approx(0.4).margin(1e-3));
    CHECK(r.free == std::vector<std::string>{"k1_capture", "k2_capture", "k_ins_capture"});
  }
  SECTION("per wavelength") {
    const SpectralData target = planted(base, "scaler-offset:spectral=400/1.1/0.02;700/0.9/0.01");
    SurfaceFitOptions o;
    o.range_min = 400;
    o.range_max = 700;
    o.per_wavelength = true;
    const SurfaceFitResult r = fit_surface({"scaler-offset", {}, {}}, base, target, o);
    CHECK(r.spectral_rms_after < 1e-7);
    const auto c = surface_coefficients(r.choice, {400, 550, 700});
    CHECK(c[0][0] == Approx(1.1).margin(1e-6));
    CHECK(c[0][1] == Approx(0.02).margin(1e-6));
    CHECK(c[1][0] == Approx(1.0).margin(1e-6));
    CHECK(c[2][1] == Approx(0.01).margin(1e-6));
    // The fitted choice applied again reproduces the corrected set.
    const SpectralData again = correct_surface(r.choice, r.measured);
    for (size_t k = 0; k < again.size(); ++k)
      for (size_t w = 0; w < again.wavelengths.size(); ++w)
        CHECK(again.values[k][w] == Approx(r.corrected.values[k][w]).margin(1e-14));
  }
}

TEST_CASE("Phase I refuses bad input with codes", "[surface][fit]") {
  const SpectralData base = sg_before();
  SpectralData fewer = base;
  fewer.names.pop_back();
  fewer.values.pop_back();
  test::require_code([&] { fit_surface({"scaler", {}, {}}, base, fewer); }, ErrorCode::PatchMismatch);
  SpectralData renamed = base;
  renamed.names[3] = "Z99";
  test::require_code([&] { fit_surface({"scaler", {}, {}}, renamed, base); }, ErrorCode::PatchMismatch);
  SurfaceFitOptions o;
  o.range_min = 350;
  o.range_max = 700;
  test::require_code([&] { fit_surface({"scaler", {}, {}}, base, base, o); }, ErrorCode::WavelengthMismatch);
  SpectralData shifted = base;
  for (auto& w : shifted.wavelengths) w += 400;  // 780-1130 nm: no common range
  test::require_code([&] { fit_surface({"scaler", {}, {}}, base, shifted); }, ErrorCode::WavelengthMismatch);
  SpectralData high = base;
  high.values[0][5] = 1.7;
  test::require_code([&] { fit_surface({"scaler", {}, {}}, high, base); }, ErrorCode::InvalidArgument);
  SpectralData negative = base;
  negative.values[2][5] = -0.2;
  test::require_code([&] { fit_surface({"scaler", {}, {}}, base, negative); }, ErrorCode::NegativeValue);
  test::require_code([&] { fit_surface(parse_choice("saunderson:k1=1.5"), base, base); }, ErrorCode::InvalidArgument);
  SurfaceFitOptions all;
  all.free = "all";
  test::require_code([&] { fit_surface({"saunderson", {}, {}}, base, base, all); }, ErrorCode::IllPosed);
  all.free = "k1+k2+k_ins+k1_capture";
  test::require_code([&] { fit_surface({"saunderson", {}, {}}, base, base, all); }, ErrorCode::IllPosed);
  all.free = "k3";
  test::require_code([&] { fit_surface({"saunderson", {}, {}}, base, base, all); }, ErrorCode::InvalidArgument);
}

// Real data: the same ColorChecker SG edition measured d:8 SCI (COOLPI, Konica Minolta CM-600d)
// and X-Rite's reference spectra (dcamprof, charts before Nov 2014, a 45:0 instrument), 400-700 nm,
// D50, 1931. Saunderson twice: the paper's advice (the d:8 SCI instrument fixed to its preset,
// the other geometry fitted), and the 45:0 side fixed with the SCI side fitted.
TEST_CASE("Phase I on the real SG in two geometries keeps the paper's ranking", "[surface][fit][real]") {
  const SpectralData from = sg_sci(), to = sg_before();
  SurfaceFitOptions o;
  o.range_min = 400;
  o.range_max = 700;
  o.observer = Observer::CIE1931_2;
  o.illuminant = illuminant_spd("D50");
  std::map<std::string, SurfaceFitResult> r;
  MethodChoice sci_to_45 = parse_choice("saunderson");
  const SaundersonGeometry sci = saunderson_preset("d8-sci").geometry, o45 = saunderson_preset("45-0").geometry;
  sci_to_45.parameters = {{"k1", sci.k1}, {"k2", sci.k2}, {"k_ins", sci.k_ins},
                          {"k1_capture", o45.k1}, {"k2_capture", o45.k2}, {"k_ins_capture", o45.k_ins}};
  for (const char* m : {"none", "scaler", "offset", "scaler-offset"}) r[m] = fit_surface({m, {}, {}}, from, to, o);
  r["saunderson"] = fit_surface(sci_to_45, from, to, o);
  SurfaceFitOptions m = o;
  m.free = "measurement";
  r["saunderson-45-0-fixed"] = fit_surface(sci_to_45, from, to, m);
  std::printf("\nSG, d:8 SCI (COOLPI XRCCSG) -> X-Rite reference (before Nov 2014), 400-700 nm, D50, 1931\n");
  std::printf("  %-22s %9s %10s %9s %9s\n", "method", "rms", "mean dE00", "max dE00", "status");
  for (const char* k : {"none", "scaler", "offset", "scaler-offset", "saunderson", "saunderson-45-0-fixed"})
    std::printf("  %-22s %9.5f %10.3f %9.3f %9s  %s\n", k, r[k].spectral_rms_after, r[k].summary_dE00_after.mean,
                r[k].summary_dE00_after.max, r[k].status.c_str(), surface_choice_text(r[k].choice).c_str());
  const double none = r["none"].summary_dE00_after.mean, scaler = r["scaler"].summary_dE00_after.mean;
  const double offset = r["offset"].summary_dE00_after.mean, so = r["scaler-offset"].summary_dE00_after.mean;
  CHECK(r["none"].summary_dE00_before.mean == Approx(none).epsilon(1e-12));
  // The paper's ranking on mean CIEDE2000: scaler ≈ none (within 15 %), offset < scaler,
  // scaler-offset < offset, Saunderson <= scaler-offset (both ways of fixing one geometry).
  CHECK(std::fabs(scaler - none) < 0.15 * none);
  CHECK(offset < scaler);
  CHECK(so < offset);
  CHECK(r["saunderson"].summary_dE00_after.mean <= so);
  CHECK(r["saunderson-45-0-fixed"].summary_dE00_after.mean <= so);
  // On the spectral RMS the fits minimise: the same order, except that with the SCI preset fixed
  // (k1 = 0.092, k_ins = 1) the scaler-offset optimum would need k_ins' = 1.28 > 1, so that fit
  // rests on the bound (status at_bound) a little above scaler-offset's RMS.
  CHECK(r["offset"].spectral_rms_after < r["scaler"].spectral_rms_after);
  CHECK(r["scaler-offset"].spectral_rms_after < r["offset"].spectral_rms_after);
  CHECK(r["saunderson-45-0-fixed"].spectral_rms_after <= r["scaler-offset"].spectral_rms_after);
  CHECK(r["saunderson"].status == "at_bound");
  CHECK(r["saunderson-45-0-fixed"].status == "ok");
}

// Shen, Xin, Yang & Lou (2008) re-run on the virtual camera: the simulation of eq (29) and the
// tables and figures it leads to, for the ColorChecker (MCC: 18 non-grey of 24; greys D1-D6) and
// the ColorChecker SG (standing in for the paper's ColorChecker DC; greys chosen automatically).
//   ρ = l·u^(1/γ) + n,  γ = 1.8, l = 22, ρ in [0, 255] (rounded), n ~ N(0, σ²), σ = 0, 1, 2, 3
//   camera: measured sensitivities (default Canon EOS 5D Mark II) under D65; white u = 80
// Prints:
//   Fig 2  colorimetric characterisation (10-term polynomial, eq 23-25), mean ΔE00 vs J, L = 1
//   Fig 3  spectral characterisation (eq 26-27), mean ΔE00 of the estimated reflectances vs J, L = 1
//   Fig 4  both vs J with L = 2 (the paper: real scans; here the same simulation at σ = 1)
//   Tables I and II: R² per channel, ΔE00 mean / std / max and spectral RMS mean / std / max, for
//          the grey-based OECF and the non-grey one with L = 0..3 (J = 8, σ = 1)
//   Fig 5  the three recovered OECFs against the grey-based ones (SG, J = 8, L = 2, σ = 1)
// Every number is a mean over --seeds noise realisations (default 5). Characterisation and OECF
// both use the non-grey patches, as in the paper.
// Usage: example_shen2008_simulation [--seeds N] [--camera NAME] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "shen2008_simulation.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/linearisation/spectral.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

std::string g_camera = "Canon_EOS_5D_Mark_II";

// One realisation of eq (29), rounded to integers as the paper's 8-bit values.
LinearisationData simulated(const std::string& chart, double sigma, uint64_t seed) {
  return test::shen2008_simulation(chart, sigma, seed, g_camera, true);
}

std::string greys_of(const std::string& chart) { return test::shen2008_greys(chart); }

struct Result {
  bool ok = false;
  Vec3 r2 = Vec3::Zero();
  Summary colorimetric, spectral, rms;  // ΔE00 (eq 23-25), ΔE00 of estimated reflectances, spectral RMS (eq 28)
};

Result characterise(const LinearisationData& d, const MethodChoice& choice) {
  Result r;
  Linearisation l;
  try {
    l = fit_linearisation(choice, d);
  } catch (const Error&) {
    return r;  // e.g. TooFewPatches for J + K > Q
  }
  std::vector<std::string> ids;
  std::vector<int> rows;
  for (size_t i = 0; i < d.ids.size(); ++i)
    if (std::find(l.greys.begin(), l.greys.end(), d.ids[i]) == l.greys.end()) {
      ids.push_back(d.ids[i]);
      rows.push_back(static_cast<int>(i));
    }
  PatchMatrix rgb(rows.size(), 3), xyz(rows.size(), 3);
  for (size_t i = 0; i < rows.size(); ++i) {
    rgb.row(i) = d.camera_RGB.row(rows[i]);
    xyz.row(i) = d.reference_XYZ.row(rows[i]);
  }
  r.r2 = l.r_squared;
  r.colorimetric = evaluate(fit("Shen2008", linearise(l, rgb), xyz).fitted, xyz, d.white).dE00;
  const SpectralEvaluation e =
      evaluate_spectral(fit_spectral(l, ids, rgb, d.reflectances), ids, rgb, d.reflectances, illuminant_spd("D65"));
  r.spectral = e.dE00_summary;
  r.rms = e.rms_summary;
  r.ok = true;
  return r;
}

/// Means over seeds (failed fits are left out and counted).
Result mean_over_seeds(const std::string& chart, double sigma, const MethodChoice& choice, int seeds, int* failed = nullptr) {
  Result m;
  int n = 0;
  auto add = [](Summary& a, const Summary& b) {
    a.mean += b.mean, a.std += b.std, a.max += b.max;
  };
  for (int s = 1; s <= seeds; ++s) {
    const Result r = characterise(simulated(chart, sigma, static_cast<uint64_t>(s)), choice);
    if (!r.ok) continue;
    ++n;
    m.r2 += r.r2;
    add(m.colorimetric, r.colorimetric);
    add(m.spectral, r.spectral);
    add(m.rms, r.rms);
  }
  if (failed) *failed = seeds - n;
  if (n == 0) return m;
  m.ok = true;
  m.r2 /= n;
  for (Summary* s : {&m.colorimetric, &m.spectral, &m.rms}) s->mean /= n, s->std /= n, s->max /= n;
  return m;
}

MethodChoice shen(int J, int L, const std::string& chart) {
  return MethodChoice{"Shen2008", {{"J", J}, {"L", L}}, {{"grey", greys_of(chart)}}};
}

void sweep_J(const char* title, bool spectral, int L, const std::vector<double>& sigmas, int seeds, int J_max) {
  for (const std::string chart : {"sg140", "cc24"}) {
    std::printf("\n%s — %s, L = %d (mean ΔE00; '-' = fewer non-grey samples than K + J)\n  J ", title, chart.c_str(), L);
    for (double s : sigmas) std::printf("   σ=%.0f", s);
    std::printf("\n");
    for (int J = 3; J <= J_max; ++J) {
      std::printf("%3d ", J);
      for (double s : sigmas) {
        const Result r = mean_over_seeds(chart, s, shen(J, L, chart), seeds);
        if (!r.ok) std::printf("  %6s", "-");
        else std::printf("  %6.2f", spectral ? r.spectral.mean : r.colorimetric.mean);
      }
      std::printf("\n");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 5;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) seeds = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--camera") && i + 1 < argc) g_camera = argv[++i];
    else if (!std::strcmp(argv[i], "--quick")) quick = true;
  }
  const std::vector<double> sigmas{0, 1, 2, 3};
  const int J_max = quick ? 10 : 14;
  std::printf("Shen et al. 2008 on the virtual camera: %s under D65, eq (29) with γ = 1.8, l = 22, 8-bit; "
              "white u = 80; K = 2; means over %d noise realisations\n", g_camera.c_str(), seeds);
  sweep_J("Fig 2: colorimetric characterisation (10-term, eq 23)", false, 1, sigmas, seeds, J_max);
  sweep_J("Fig 3: spectral characterisation (eq 27), ΔE00 of the estimated reflectances under D65", true, 1, sigmas,
          seeds, J_max);
  if (!quick) {
    sweep_J("Fig 4: colorimetric characterisation", false, 2, {1}, seeds, J_max);
    sweep_J("Fig 4: spectral characterisation", true, 2, {1}, seeds, J_max);
  }

  const double sigma = 1;
  for (const std::string chart : {"cc24", "sg140"}) {
    std::printf("\nTables I and II — %s, J = 8, σ = %.0f (R²: correlation with the grey-based OECF)\n", chart.c_str(), sigma);
    std::printf("  %-12s %7s %7s %7s | %6s %6s %6s | %6s %6s %6s | %6s %6s %6s\n", "", "R² R", "R² G", "R² B",
                "col.", "std", "max", "spec.", "std", "max", "rms", "std", "max");
    const MethodChoice grey{"grey-polynomial", {{"K", 2}}, {{"grey", greys_of(chart)}}};
    std::vector<std::pair<std::string, MethodChoice>> rows{{"grey-based", grey}};
    for (int L = 0; L <= 3; ++L) rows.push_back({"L = " + std::to_string(L), shen(8, L, chart)});
    for (const auto& [name, choice] : rows) {
      const Result r = mean_over_seeds(chart, sigma, choice, seeds);
      if (name == "grey-based") std::printf("  %-12s %7s %7s %7s |", name.c_str(), "-", "-", "-");
      else std::printf("  %-12s %7.4f %7.4f %7.4f |", name.c_str(), r.r2[0], r.r2[1], r.r2[2]);
      std::printf(" %6.2f %6.2f %6.2f | %6.2f %6.2f %6.2f | %6.3f %6.3f %6.3f\n", r.colorimetric.mean, r.colorimetric.std,
                  r.colorimetric.max, r.spectral.mean, r.spectral.std, r.spectral.max, r.rms.mean, r.rms.std, r.rms.max);
    }
  }

  // Fig 5: one realisation, the recovered curves against the grey-based ones (normalised to 1 at
  // the top of each channel's range), and the true inverse OECF u ∝ ρ^γ for reference.
  const LinearisationData d = simulated("sg140", sigma, 1);
  const Linearisation l = fit_linearisation(shen(8, 2, "sg140"), d);
  std::printf("\nFig 5 — sg140, J = 8, L = 2, σ = %.0f: normalised linear response vs ρ (greys: %zu)\n", sigma, l.greys.size());
  std::printf("  %5s | %-26s | %-26s | %-26s\n", "", "R: non-grey grey true", "G: non-grey grey true", "B: non-grey grey true");
  for (int i = 0; i <= 10; ++i) {
    std::printf("  %5s |", "");
    for (int c = 0; c < 3; ++c) {
      const CurveSamples s = sample_curve(l, c, 11);
      const double x = s.x[static_cast<size_t>(i)], top = s.x.back();
      std::printf(" ρ=%3.0f %6.3f %6.3f %6.3f |", x * 255, s.linear[static_cast<size_t>(i)],
                  s.grey_based[static_cast<size_t>(i)], std::pow(x / top, 1.8));
    }
    std::printf("\n");
  }
  std::printf("  R² per channel: %.5f %.5f %.5f%s%s\n", l.r_squared[0], l.r_squared[1], l.r_squared[2],
              l.message.empty() ? "" : "; ", l.message.c_str());
  return 0;
}

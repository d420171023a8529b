// The sensitivity-estimate uncertainty study: each of the 52 built-in cameras held out of the
// basis, photographed (virtual camera, linear RGB) on a ColorChecker under D65, its sensitivities
// estimated (Jiang et al. 2013, K = 4) with the stated uncertainty of A_R/A_G and A_B/A_G
// (sensitivity_uncertainty: leave-one-camera-out bases and K ± 1, coverage 2). Prints one row
// per camera — the ratios' errors against the truth, the stated band, inside or not, the
// residual and the distance to the nearest basis camera — and the coverage over the 52.
//   example_sensitivity_uncertainty [--noise 0.002] [--cameras N]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/sensitivities.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

int main(int argc, char** argv) {
  double noise = 0;
  size_t cameras = 1000;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--noise")) noise = std::atof(argv[i + 1]);
    if (!std::strcmp(argv[i], "--cameras")) cameras = static_cast<size_t>(std::atoi(argv[i + 1]));
  }
  const SpectralData refl = chart_reflectances("cc24"), d65 = illuminant_spd("D65");
  std::printf("| held-out camera | A_R/A_G error | stated ±u | inside | A_B/A_G error | stated ±u | inside | residual | nearest (RMS) | warnings |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  int inside = 0, n = 0, warned = 0;
  double max_residual = 0, max_distance = 0;
  const auto names = camera_names();
  for (size_t k = 0; k < names.size() && k < cameras; ++k) {
    const std::string& cam = names[k];
    const SpectralData truth = camera_ssf(cam);
    SimulationOptions so;
    so.noise_sigma = noise;
    so.seed = 11;
    const auto rgb = simulate_camera_RGB(truth, refl, d65, so);
    SensitivityOptions o;
    o.exclude_cameras = {cam};
    const SensitivityEstimate e = estimate_sensitivities_Jiang2013(rgb, refl, d65, o);
    const SensitivityUncertainty u = sensitivity_uncertainty(rgb, refl, d65, o, e);
    const auto A = channel_areas(truth);
    const double err[2] = {u.ratio[0] / (A[0] / A[1]) - 1, u.ratio[1] / (A[2] / A[1]) - 1};
    const bool in[2] = {std::fabs(err[0]) <= u.u[0], std::fabs(err[1]) <= u.u[1]};
    inside += in[0] + in[1];
    n += 2;
    warned += !u.warnings.empty();
    max_residual = std::max(max_residual, e.residual_rms);
    max_distance = std::max(max_distance, u.nearest_distance);
    std::string w;
    for (const auto& x : u.warnings) w += (w.empty() ? "" : " ") + x;
    std::printf("| %s | %+.2f %% | %.2f %% | %s | %+.2f %% | %.2f %% | %s | %.2f %% | %.3f | %s |\n", cam.c_str(), 100 * err[0],
                100 * u.u[0], in[0] ? "yes" : "no", 100 * err[1], 100 * u.u[1], in[1] ? "yes" : "no", 100 * e.residual_rms,
                u.nearest_distance, w.empty() ? "-" : w.c_str());
  }
  std::printf("\nCoverage (noise %.3g): %d of %d ratios inside their stated band (%.0f %%); %d of %zu cameras warned; "
              "largest residual %.2f %%, largest distance to the nearest basis camera %.3f\n",
              noise, inside, n, 100.0 * inside / n, warned, std::min(cameras, names.size()), 100 * max_residual, max_distance);
  return 0;
}

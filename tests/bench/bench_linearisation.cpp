// Output lines "BENCH <case> <step> <ms>" and "CASE <case> <text>" are read by scripts/bench.sh
// (native and wasm side by side); the other lines are for a human running it directly.
// Benchmark: the non-grey OECF (Shen et al. 2008, J = 8, L = 2, K = 2) on 140 patches (the
// ColorChecker SG simulated by eq 29), cold (the built-in Munsell set parsed and its PCA made)
// and warm; and spectral reconstruction (eq 26, 31 bands 400-700 nm) of a 24 MP image, in strips
// of 1 MP, next to a memcpy of the same output bytes. Prints figures; asserts nothing.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "bench_util.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/linearisation/spectral.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;
using namespace tristim::bench;

namespace {

LinearisationData sg_simulated() {
  const SpectralData refl = chart_reflectances("sg140");
  const SpectralData d65 = illuminant_spd("D65");
  SimulationOptions o;
  o.white_level = 80;
  o.oecf = true;
  o.noise_sigma = 1;
  o.clip_max = 255;
  const auto rgb = simulate_camera_RGB(camera_ssf("Canon_EOS_5D_Mark_II"), refl, d65, o);
  LinearisationData d;
  d.ids = refl.names;
  d.reflectances = refl;
  d.full_scale = 255;
  d.camera_RGB.resize(static_cast<Eigen::Index>(rgb.size()), 3);
  for (size_t i = 0; i < rgb.size(); ++i) d.camera_RGB.row(static_cast<Eigen::Index>(i)) = rgb[i].transpose();
  return d;
}

}  // namespace

int main() {
  const LinearisationData d = sg_simulated();
  // use_greys: every one of the 140 patches takes part (the SG's greys would otherwise be left out).
  const MethodChoice choice{"Shen2008", {{"J", 8}, {"L", 2}, {"K", 2}, {"use_greys", 1}}, {}};
  std::printf("== Shen 2008 non-grey OECF, J = 8, L = 2, K = 2, 140 patches ==\n");
  const auto t0 = Clock::now();
  Linearisation lin = fit_linearisation(choice, d);
  const double cold = ms_since(t0);
  const double warm = best_ms(20, [&] { lin = fit_linearisation(choice, d); });
  std::printf("  cold (parse 1269 Munsell chips, PCA) %8.2f ms\n  warm                                 %8.2f ms\n", cold, warm);
  std::printf("CASE oecf_Shen2008_140 J=8 L=2 K=2 on the simulated SG (140 patches): warm %.2f ms, cold %.1f ms\n", warm, cold);
  std::printf("BENCH oecf_Shen2008_140 warm %.3f\n", warm);
  std::printf("BENCH oecf_Shen2008_140 cold %.3f\n", cold);

  // Spectral model on 400-700 nm at 10 nm (the paper's N = 31).
  SpectralData refl = align_spectra(d.reflectances, wavelength_grid(400, 700, 10));
  const SpectralModel model = fit_spectral(lin, d.ids, d.camera_RGB, refl);
  const size_t w = 6000, h = 4000, n = w * h, strip = 1000000, N = model.wavelengths.size();
  std::vector<float> rgb(3 * n);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(20 + (i * 7919 % 2300) * 0.1);
  std::vector<float> out(strip * N), copy_src(strip * N, 0.5f);
  const double t_spec = best_ms(3, [&] {
    for (size_t s = 0; s < n; s += strip) estimate_reflectance_image(model, rgb.data() + 3 * s, std::min(strip, n - s), out.data());
  });
  const double t_copy = best_ms(3, [&] {
    for (size_t s = 0; s < n; s += strip) std::memcpy(out.data(), copy_src.data(), std::min(strip, n - s) * N * 4);
  });
  const double gb = static_cast<double>(n) * N * 4 / 1e9;
  std::printf("\n== spectral reconstruction, %zux%zu, %zu bands (%.1f GB of output, 1 MP strips) ==\n", w, h, N, gb);
  std::printf("  memcpy of the output bytes %8.1f ms  (%.2f GB/s)\n", t_copy, gb / t_copy * 1e3);
  std::printf("  linearise + W (eq 26)      %8.1f ms  (%.2f GB/s) = %.0f %% of memcpy bandwidth\n", t_spec,
              gb / t_spec * 1e3, 100 * t_copy / t_spec);
  std::printf("CASE spectral_24MP %zux%zu RGB -> %zu bands (Shen2008 linearisation + W): %.0f %% of memcpy bandwidth\n", w, h,
              N, 100 * t_copy / t_spec);
  std::printf("BENCH spectral_24MP memcpy %.2f\n", t_copy);
  std::printf("BENCH spectral_24MP reconstruct %.2f\n", t_spec);

  // A fixed curve applied to a whole 24 MP image (linearise_image, as `tristim apply` runs a
  // profile with a gamma or sRGB stage): samples with fractions (as a RAW decode gives) are 72 M
  // calls of detmath's pow (the same bits natively and in wasm), next to the same loop with the C
  // library's pow.
  std::printf("\n== linearise a 24 MP image ==\n");
  std::vector<float> img(rgb.size());
  // One row per curve on `source` (stored values of the given full scale); `suffix` names the image.
  const auto curve_rows = [&](const std::vector<float>& source, double full_scale, const char* suffix) {
    LinearisationData none;
    none.camera_RGB = PatchMatrix::Constant(1, 3, 100);
    none.full_scale = full_scale;
    for (const char* id : {"gamma", "sRGB"}) {
      const Linearisation fixed = fit_linearisation(MethodChoice{id, {}, {}}, none);
      const double t = best_ms(1, [&] {
        std::copy(source.begin(), source.end(), img.begin());
        linearise_image(fixed, img.data(), n);
      });
      std::printf("  %-6s%-7s %8.1f ms\n", id, suffix, t);
      std::printf("BENCH linearise_24MP %s%s %.1f\n", id, suffix, t);
    }
  };
  curve_rows(rgb, 255, "");
  // The same curves on a 16-bit image (whole numbers 0..65535, as from a 16-bit TIFF or PNG): a
  // table per channel, filled on first use (linearise_image).
  std::vector<float> img16(rgb.size());
  for (size_t i = 0; i < img16.size(); ++i) img16[i] = static_cast<float>(i * 7919 % 65536);
  curve_rows(img16, 65535, "-16bit");
  const double t_libm = best_ms(1, [&] {
    for (size_t i = 0; i < rgb.size(); ++i) img[i] = static_cast<float>(std::pow(rgb[i] / 255.0, 2.2));
  });
  std::printf("  the C library's pow, same loop %8.1f ms\n", t_libm);
  std::printf("BENCH linearise_24MP libm-pow-loop %.1f\n", t_libm);
  std::printf("CASE linearise_24MP gamma / sRGB curve on 72 M samples (detmath pow), and a loop of the C library's pow\n");
  return 0;
}

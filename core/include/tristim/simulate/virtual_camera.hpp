// The virtual camera: camera RGB of reflectances under an illuminant through measured spectral
// sensitivities (SSF), with optional seeded noise, OECF and quantisation. Later methods test
// themselves on it (planted solutions with a known spectral truth).
//
//   u_c = k Σ_λ SSF_c(λ) S(λ) R(λ)                               (linear response, channel c)
//   k   = white_level / Σ_λ SSF_G(λ) S(λ)                        (perfect diffuser: G = white_level)
// summed on the SSF's own wavelength grid (the measured samples, not interpolated); S and R are
// aligned to it by the spectra.hpp rule (Sprague/linear, constant extrapolation).
// Then, optionally (Shen, Xin, Yang & Lou 2008, eq 29: ρ = l·u^(1/γ) + n, noise in the non-linear space):
//   OECF:   ρ = l · u^(1/γ)          (u < 0 -> 0)
//   noise:  + n, n ~ N(0, σ²), seeded (noise is added after the OECF when there is one, else to u)
//   clip:   to [0, clip_max] if clip_max > 0
//   quantise: round to the nearest integer (after clipping) if quantise is set.
#pragma once
#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

/// Names of the 52 built-in cameras (rawtoaces-data, e.g. "Canon_EOS_5D_Mark_II").
std::vector<std::string> camera_names();
/// Spectral sensitivities of a built-in camera: columns "R","G","B", 380-780 nm at 5 nm, relative.
/// The name is matched ignoring case and treating spaces, '-' and '_' alike
/// ("canon eos 5d mark ii" works). Error(UnknownId) otherwise.
SpectralData camera_ssf(std::string_view name);
/// SSF from a CSV: first column wavelength, then three columns R, G, B (named R/G/B, *_R/*_G/*_B,
/// red/green/blue, or simply the three columns in that order).
SpectralData read_ssf_csv(std::string_view text, std::string_view source);

struct SimulationOptions {
  double white_level = 1.0;  ///< linear G response of the perfect diffuser
  double noise_sigma = 0;    ///< standard deviation of the additive Gaussian noise (output units)
  uint64_t seed = 1;         ///< noise seed (same seed -> same numbers, native and wasm)
  bool oecf = false;         ///< apply ρ = l·u^(1/γ) (Shen, Xin, Yang & Lou 2008 eq 29)
  double oecf_gamma = 1.8;   ///< γ
  double oecf_scale = 22;    ///< l
  double clip_max = 0;       ///< clip to [0, clip_max] when > 0 (Shen: 255)
  bool quantise = false;     ///< round to integers (after clipping)
};

/// Camera RGB (N x 3, one row per column of `reflectances`).
std::vector<Vec3> simulate_camera_RGB(const SpectralData& ssf, const SpectralData& reflectances,
                                      const SpectralData& illuminant, const SimulationOptions& options = {});

/// Deterministic standard normal deviates (Box-Muller on the standard-specified mt19937_64, so the
/// sequence is the same with any C++ library; std::normal_distribution is not).
class GaussianNoise {
 public:
  explicit GaussianNoise(uint64_t seed);
  double next();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

}  // namespace tristim

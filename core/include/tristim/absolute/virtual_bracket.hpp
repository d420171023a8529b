// A virtual camera for bracketed RAW frames: the test bench of the absolute chain (Guarnera 2018
// section 3.1's sensor model, eqs 5-7, run forwards). Built on the virtual camera's measured
// sensitivities (simulate/virtual_camera.hpp: 52 real cameras).
//
// A scene is a set of stimuli — relative spectral radiances on the camera's wavelength grid, each
// with an absolute luminance Y in cd/m² — and a label per measurement pixel (optionally times a
// per-pixel luminance gain). For stimulus s with spectrum φ(λ) and channel c:
//   q_c = Σ SSF_c·φ / Σ ȳ·φ · Σ ȳ / Σ SSF_G           (response per cd/m²; q_G = 1 for light E)
//   u_c = Y·q_c·ε_eff / H_sat / f(r)                 (linear, 1 = the clip at the image centre)
//   ε_eff = t_ref·(t/t_ref)^p / N² · ISO/100          (t_ref = 1/60 s; p = 1: reciprocity holds)
// then, per sensor pixel (R, two G, B of a 2×2 Bayer block):
//   shot noise      e = u_c·(S − n)·g + √(u_c·(S − n)·g)·N(0,1)   (g electrons per DN)
//   OECF            v = (e/((S − n)·g))^k3_c                       (power law, signed)
//   DN              n + (S − n)·v + σ_read·N(0,1), clipped at S, rounded
// and the measurement pixel is (R, mean of the greens, B), as decode_raw makes it. X, Y, Z of a
// stimulus: Y·Σ x̄φ/Σ ȳφ, Y, Y·Σ z̄φ/Σ ȳφ with the CIE 1931 2° functions sampled on the same grid.
// The metadata claim `reported_saturation` (LibRaw's maximum may be optimistic: the decoder's
// 98 % flag then never fires and S must be measured from the data).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/absolute/luminance.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

struct VirtualSensor {
  SpectralData ssf;                    ///< R, G, B sensitivities (e.g. camera_ssf(name))
  std::string make = "tristim", model = "Virtual bracket camera";
  double saturation = 15000;           ///< S: where the sensor really clips (DN, black-subtracted)
  double reported_saturation = 16000;  ///< what the metadata says (RawMetadata::saturation)
  double noise_floor = 8;              ///< n: mean dark level left after the black level (DN)
  double read_noise = 3;               ///< σ of the read noise (DN)
  double electrons_per_dn = 2.5;       ///< conversion gain g (shot noise); 0: no shot noise
  double saturation_exposure = 0.25;   ///< H_sat = Y·ε (cd·s/m²) at which G clips at the centre for light E
  std::array<double, 3> oecf_exponent{{1.0, 1.0, 1.0}};  ///< k3 per channel of the true OECF
  double falloff_p1 = 0.3, falloff_p2 = 0.0;  ///< the lens passes 1/f(r), f = p1 r² + p2 r + 1
  double reciprocity_exponent = 1;     ///< p (≠ 1: reciprocity failure)
  bool quantise = true;
};

struct VirtualScene {
  int width = 0, height = 0;
  SpectralData stimuli;                ///< one column per stimulus: relative spectral radiance
  std::vector<double> luminance;       ///< Y of each stimulus, cd/m²
  std::vector<std::uint16_t> label;    ///< width·height stimulus indices
  std::vector<float> gain;             ///< optional width·height luminance multipliers (empty: 1)
};

/// Stimulus spectra: reflectances (columns) times an illuminant, on the reflectances' grid.
SpectralData reflected_spectra(const SpectralData& reflectances, const SpectralData& illuminant);
/// One equal-energy stimulus (φ = 1, X = Y = Z) on 380-780 nm at 5 nm, named `name`.
SpectralData equal_energy_spectrum(const std::string& name = "E");

/// The paper's light source (section 4: a calibrated DLP projector on a white diffuser): three
/// primaries — a flat lamp through smooth band filters, B 400-500 nm, G 490-580 nm, R 580-700 nm
/// (logistic edges, 8 nm) — mixed to give each target's chromaticity. Targets outside the
/// primaries' gamut get the nearest mixture with non-negative weights (the achieved XYZ is what
/// virtual_XYZ reports, as the paper measured its stimuli). Columns: relative radiance on
/// 380-780 nm at 5 nm, named `names` (or "1".."N"); set their luminance in the scene.
/// projector_primaries(): the three primaries themselves (columns "R", "G", "B").
SpectralData projector_primaries();
SpectralData projector_spectra(const std::vector<Vec3>& target_XYZ, const std::vector<std::string>& names = {});

/// A scene of one stimulus everywhere.
VirtualScene uniform_scene(int width, int height, const SpectralData& spectrum, double luminance);

/// X, Y, Z (cd/m²) of stimulus k of the scene (times `gain`), with the rule above.
Vec3 virtual_XYZ(const VirtualSensor& sensor, const VirtualScene& scene, int k, double gain = 1);

/// One RAW frame of the scene at `exposure` (measurement pixels; metadata: make, model, t, N,
/// ISO, layout "bayer", block 2, saturation = reported_saturation; saturated flags as decode_raw
/// sets them, at 98 % of the reported level). Noise from `seed` (same seed, same frame).
RawImage capture_virtual(const VirtualSensor& sensor, const VirtualScene& scene,
                         const ExposureSettings& exposure, std::uint64_t seed);

/// A colour training stimulus as the virtual experiments shoot one: stimulus k of `spectra` alone
/// filling a width × height frame at `luminance` (cd/m²), one frame at `exposure` (noise from
/// `seed`), sampled in the 8 × 8 window at the centre with `n`; its X, Y, Z by virtual_XYZ.
TrainingStimulus shoot_colour_stimulus(const VirtualSensor& sensor, const SpectralData& spectra, size_t k,
                                       double luminance, int width, int height, const ExposureSettings& exposure,
                                       std::uint64_t seed, const Normalisation& n, const std::string& id);

/// The same frame as sensor values: a (2·width) × (2·height) RGGB mosaic in DN plus `black`
/// (clamped to 0..65535), e.g. for a DNG with black level `black` and white level
/// `reported_saturation` + `black`; decoding it gives capture_virtual's image (same seed, same
/// numbers) where no value was clamped — read noise takes dark values below 0 DN, which a black
/// level of a few σ above 0 keeps (64 for the default sensor).
std::vector<std::uint16_t> capture_virtual_mosaic(const VirtualSensor& sensor, const VirtualScene& scene,
                                                  const ExposureSettings& exposure, std::uint64_t seed,
                                                  int black = 0);

}  // namespace tristim

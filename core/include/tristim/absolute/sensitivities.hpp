// Camera spectral sensitivities for eq (7)'s channel areas A_R, A_G, A_B (Guarnera 2018 section
// 3.1): built in (the 52 measured cameras of simulate/virtual_camera.hpp), from a CSV, or
// estimated from one photo of a chart with known reflectances under a known illuminant, the
// method the paper cites:
//   H. Jiang, D. Liu, J. Gu, S. Süsstrunk, "What is the space of spectral sensitivity functions
//   for digital color cameras?", IEEE WACV 2013 — sensitivities lie in a low-dimensional space:
//   per channel, a few principal components of measured cameras' curves span them.
// Here the basis is built from the built-in cameras (optionally leaving some out), per channel:
// every curve scaled to unit norm, the first K right singular vectors of the cameras × λ matrix
// (uncentred, so the mean shape is the first). With A_iλ = r_i(λ)·S(λ)·Δλ (reflectance times
// illuminant) and ρ_c the camera's linear responses to the N patches, channel c solves
//   min_σ ‖A·B_c·σ − ρ_c‖² + μ·‖D₂·B_c·σ‖²,  μ = smoothness · tr(BᵀAᵀAB)/tr(BᵀD₂ᵀD₂B)
// (D₂: second differences along λ, the smoothness constraint), negative values of the curve set
// to 0. The channels keep their relative scale (the RGB values are not white balanced); the
// result is scaled by one factor so that the largest value of the three curves is 1.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

struct SensitivityOptions {
  int components = 4;          ///< K principal components per channel (1..12)
  double smoothness = 1e-3;    ///< μ relative to the data term (0: none)
  std::vector<std::string> exclude_cameras;  ///< built-in cameras left out of the basis
};

struct SensitivityEstimate {
  SpectralData ssf;            ///< columns R, G, B on 380-780 nm at 5 nm, max of the three = 1
  Vec3 residual = Vec3::Zero();  ///< per channel: RMS(predicted − measured ρ)/RMS(measured ρ)
  double residual_rms = 0;     ///< the same over all channels
  int patches = 0, components = 0, basis_cameras = 0;
  std::array<double, 3> areas{};  ///< A_R, A_G, A_B of the estimate (channel_areas)
  int clipped = 0;             ///< samples set to 0 because the solve went negative
  std::vector<std::string> ids;  ///< the patches used, in order (estimate_sensitivities_by_id)
  int unpaired = 0;            ///< camera RGB rows without a reflectance of the same id (by_id)
};

/// Estimates the sensitivities from linear camera RGB (N patches, black-subtracted, no white
/// balance) of patches with known `reflectances` (columns in the same order as camera_RGB,
/// fractions) under `illuminant` (first column). Errors: PatchMismatch (counts differ),
/// TooFewPatches (N < K), InvalidArgument (K out of range, negative smoothness, non-positive
/// responses in a channel), UnknownId (an excluded camera that is not built in), NonFinite.
SensitivityEstimate estimate_sensitivities_Jiang2013(const std::vector<Vec3>& camera_RGB,
                                                     const SpectralData& reflectances,
                                                     const SpectralData& illuminant,
                                                     const SensitivityOptions& options = {});

/// Pairs per-patch camera RGB (`ids`, one per row) with the reflectance columns of the same
/// patch id (compared after normalise_patch_id: "A01" = "A1"), then
/// estimate_sensitivities_Jiang2013 on the pairs. Rows without a reflectance are left out and
/// counted in `unpaired`. Errors: PatchMismatch (ids and rows differ in count, or no id pairs),
/// and those of estimate_sensitivities_Jiang2013.
SensitivityEstimate estimate_sensitivities_by_id(const std::vector<std::string>& ids,
                                                 const std::vector<Vec3>& camera_RGB,
                                                 const SpectralData& reflectances,
                                                 const SpectralData& illuminant,
                                                 const SensitivityOptions& options = {});

/// RMS difference of two sets of sensitivities with each channel scaled to peak 1, over the
/// common 5 nm grid of `a` (b interpolated): how well the shapes agree.
double sensitivity_rms(const SpectralData& a, const SpectralData& b);

/// Sensitivities as CSV "wavelength_nm,R,G,B", all three scaled by one factor so that the
/// largest value is 1 (the channel ratios eq 7 needs are kept).
std::string sensitivities_to_csv(const SpectralData& ssf);

}  // namespace tristim

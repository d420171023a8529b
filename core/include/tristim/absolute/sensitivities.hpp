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
// Its JSON (field list in tristim/absolute/fields.hpp): what `tristim sensitivities estimate`
// prints and the page gets — {method: "Jiang2013", patches, unpaired, components, basis_cameras,
// residual, residual_rms, areas, area_ratio_R_G, area_ratio_B_G (written from areas), clipped, ids,
// ssf: {wavelengths, names, values}}.

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

/// How sure an estimate's channel areas are, and whether the camera looks like the basis cameras.
/// Eq (7) uses the areas' ratios, so the uncertainty is stated for A_R/A_G and A_B/A_G:
///   u_LOO: jackknife standard deviation over the leave-one-camera-out bases (the estimate made
///          again with each basis camera left out in turn: sqrt((n−1)/n · Σ(θ_i − θ̄)²));
///   u_K:   half the range of the ratio over K − 1, K, K + 1 components (those the patches allow);
///   u = coverage · sqrt(u_LOO² + u_K²), relative to the ratio (coverage 3 by default; the study
///   in examples/sensitivity_uncertainty checks how often the truth lies within ±u).
/// Warnings (codes): "OUTSIDE_BASIS_RESIDUAL" when residual_rms exceeds residual_limit (the
/// basis cannot reproduce the camera's responses), "OUTSIDE_BASIS_DISTANCE" when the estimate's
/// sensitivity_rms to the nearest basis camera exceeds distance_limit. The limits are above every
/// one of the 52 cameras estimated with itself left out (ColorChecker, D65: the same study).
struct SensitivityUncertainty {
  std::array<double, 2> ratio{};          ///< A_R/A_G, A_B/A_G of the estimate
  std::array<double, 2> u_loo{}, u_K{};   ///< relative standard uncertainties (fractions of the ratio)
  std::array<double, 2> u{};              ///< coverage · combined, relative
  double coverage = 3;
  int loo_bases = 0;                      ///< estimates over leave-one-camera-out bases
  std::vector<int> components_tried;      ///< the K values of u_K
  std::string nearest_camera;             ///< the basis camera closest to the estimate
  double nearest_distance = 0;            ///< sensitivity_rms to it
  double residual_limit = 0, distance_limit = 0;
  std::vector<std::string> warnings;      ///< codes (above), empty when the camera looks like the basis
  std::string message;                    ///< one line per warning, "" when none
};
struct SensitivityUncertaintyOptions {
  double coverage = 3;            ///< the study (docs/methods.md): k = 3 holds 97 % of the 52 held-out cameras' ratios (k = 2: 84 %)
  double residual_limit = 0.02;   ///< residual_rms above this: outside the basis (the 52 held out: at most 0.73 %)
  double distance_limit = 0.10;   ///< distance to the nearest basis camera above this (the 52 held out: at most 0.088)
};

/// The uncertainty of `estimate` (made by estimate_sensitivities_Jiang2013 from these inputs and
/// `options`): re-estimates over the leave-one-camera-out bases and over K ± 1 (about 55
/// solves). Errors: those of estimate_sensitivities_Jiang2013.
SensitivityUncertainty sensitivity_uncertainty(const std::vector<Vec3>& camera_RGB, const SpectralData& reflectances,
                                               const SpectralData& illuminant, const SensitivityOptions& options,
                                               const SensitivityEstimate& estimate,
                                               const SensitivityUncertaintyOptions& u = {});

/// sensitivity_uncertainty of an estimate made by estimate_sensitivities_by_id from these inputs:
/// the camera RGB rows paired by id with the reflectances as that function pairs them.
SensitivityUncertainty sensitivity_uncertainty_by_id(const std::vector<std::string>& ids,
                                                     const std::vector<Vec3>& camera_RGB,
                                                     const SpectralData& reflectances, const SpectralData& illuminant,
                                                     const SensitivityOptions& options,
                                                     const SensitivityEstimate& estimate,
                                                     const SensitivityUncertaintyOptions& u = {});

/// RMS difference of two sets of sensitivities with each channel scaled to peak 1, over the
/// common 5 nm grid of `a` (b interpolated): how well the shapes agree.
double sensitivity_rms(const SpectralData& a, const SpectralData& b);

/// Sensitivities as CSV "wavelength_nm,R,G,B", all three scaled by one factor so that the
/// largest value is 1 (the channel ratios eq 7 needs are kept).
std::string sensitivities_to_csv(const SpectralData& ssf);

}  // namespace tristim

// ACES Input Device Transforms (IDT): white-balanced camera RGB -> ACES2065-1, the method of the
// Academy's P-2013-001 ("Recommended Procedures for the Creation and Use of Digital Camera System
// Input Device Transforms") as rawtoaces v1 and colour-science's `matrix_idt` implement it
// (Dyer, Forsythe, Irons, Mansencal & Zhu 2017, "RAW to ACES" v1):
//
//   training set  190 reflectances (rawtoaces-data, 380-780 nm at 5 nm) or the user's own, or a
//                 photographed chart's patches with their reference XYZ;
//   spectral grid 380-780 nm at 5 nm (rawtoaces' shape); every distribution is re-sampled to it
//                 (spectra.hpp rule) and sums replace integrals, as in rawtoaces and colour;
//   illuminant    I(λ), scaled by k = 1 / Σ I·S_c, c the channel whose sensitivity peaks highest;
//   camera RGB    ρ_c = Σ I·R·S_c; white balance, G = 1, from the perfect diffuser's ρ(white):
//                 w = (ρ_G(white)/ρ_R(white), 1, ρ_G(white)/ρ_B(white)), and the white-balanced
//                 RGB is ρ·w / ρ_G(white), so the perfect diffuser is (1, 1, 1);
//   target        XYZ = Σ I·R·x̄ / Σ I·ȳ (CIE 1931 2°), adapted from the illuminant's white to the
//                 ACES white (xy 0.32168, 0.33767) by a von Kries transform in CAT02 or Bradford
//                 space (colour's `training_data_sds_to_XYZ`);
//   matrix        B (3×3) with every row summing to one (the white stays neutral: B·1 = 1), six
//                 free entries, minimising Σ_patches ΔE*ab² between L*a*b*(NPM_AP0·B·ρ) and
//                 L*a*b*(XYZ), both against the ACES white (rawtoaces v1's objective; colour's
//                 `optimisation_factory_rawtoaces_v1`, the norm of all residuals). Solved here by
//                 Levenberg–Marquardt with the exact Jacobian, from B = I.
// ACES2065-1 = B · diag(w) · camera RGB (camera-native, linear, black subtracted): a camera value
// of 1 in G for the perfect diffuser gives ACES (1, 1, 1).
// When G is also the channel of largest response (every camera of the built-in set) w and the
// white-balanced RGB equal colour-science's (its multipliers are normalised to their minimum).
//
// From a chart (camera RGB of patches + their reference XYZ under the illuminant): the white
// balance comes from the most neutral bright patch (reference C*ab ≤ 4, the highest L*; failing
// that the smallest C*ab), scaled so its white-balanced G equals its reference Y (white Y = 1).
#pragma once
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

/// ACES2065-1 (AP0 primaries, white xy 0.32168, 0.33767; SMPTE ST 2065-1) -> CIE XYZ (Y = 1), the
/// normalised primary matrix of SMPTE RP 177.
Mat3 aces2065_1_to_XYZ();
/// The ACES white, XYZ with Y = 1.
Vec3 aces_white_XYZ();

/// The 190 training reflectances of rawtoaces v1 (rawtoaces-data, Apache-2.0), 380-780 nm, 5 nm.
const SpectralData& idt_training_190();

struct IdtOptions {
  ChromaticAdaptation adaptation = ChromaticAdaptation::CAT02;  ///< CAT02 or Bradford
};

/// An IDT and how well it fits its training set.
struct IdtResult {
  Mat3 matrix = Mat3::Identity();   ///< B: white-balanced camera RGB -> ACES2065-1, rows sum to 1
  Vec3 white_balance = Vec3::Ones(); ///< w: multipliers R, G, B with G = 1
  /// Camera value -> white-balanced RGB scale: 1 from sensitivities (a perfect diffuser whose G is
  /// 1 gives ACES 1, 1, 1); from a chart, the neutral patch's reference Y over its camera G.
  double exposure = 1;
  /// The CLF/plain matrix of camera-native RGB: exposure·B·diag(w).
  Mat3 camera_matrix() const { return exposure * matrix * white_balance.asDiagonal(); }
  std::string adaptation;           ///< "CAT02" or "Bradford"
  int patches = 0;
  std::vector<double> delta_E76;    ///< per training sample: ΔE*ab against the ACES white (the objective)
  std::vector<double> delta_E00;    ///< per training sample: CIEDE2000, same L*a*b*
  double mean_delta_E76 = 0, max_delta_E76 = 0, mean_delta_E00 = 0, max_delta_E00 = 0;
  double objective = 0;             ///< sqrt(Σ ΔE*ab²), colour-science's objective value
  int iterations = 0;
  std::string status = "ok";        ///< "ok" or "warning" (message says why)
  std::string message;
  std::vector<Vec3> white_balanced_RGB;  ///< ρ·w scaled, one per sample
  std::vector<Vec3> target_XYZ;          ///< adapted to the ACES white, Y of the white = 1
};

/// The camera RGB and adapted XYZ of a training set as the header states (spectral path).
struct IdtTraining {
  std::vector<Vec3> white_balanced_RGB, target_XYZ;
  Vec3 white_balance;
};
/// Error(InvalidArgument) for an SSF without 3 columns or a zero response, WavelengthMismatch when
/// sensitivities, illuminant and reflectances share no part of 380-780 nm.
IdtTraining idt_training_from_spectra(const SpectralData& sensitivities, const SpectralData& illuminant,
                                      const SpectralData& reflectances, ChromaticAdaptation adaptation);

/// Fits B to white-balanced RGB and adapted XYZ (both N×3, white = 1). Error(TooFewPatches) under
/// 3 samples, NonFinite for a non-finite value, FitFailed if the solver cannot descend.
IdtResult fit_idt(const std::vector<Vec3>& white_balanced_RGB, const std::vector<Vec3>& target_XYZ,
                  const Vec3& white_balance, const IdtOptions& options = {});

/// The IDT of a camera with known spectral sensitivities (columns R, G, B) under `illuminant`
/// with `reflectances` as the training set (idt_training_190() by default).
IdtResult idt_from_sensitivities(const SpectralData& sensitivities, const SpectralData& illuminant,
                                 const SpectralData& reflectances, const IdtOptions& options = {});

/// The IDT from a photographed chart: camera RGB (linear, black subtracted) and the patches'
/// reference XYZ under the illuminant whose white is `illuminant_white_XYZ` (any scale; the
/// reference in the same scale). Error(NegativeValue) for a negative camera white,
/// TooFewPatches under 3 patches, InvalidArgument for sizes that differ.
IdtResult idt_from_patches(const std::vector<Vec3>& camera_RGB, const std::vector<Vec3>& reference_XYZ,
                           const Vec3& illuminant_white_XYZ, const IdtOptions& options = {});

/// "CAT02" / "Bradford" (case-insensitive) -> the transform; Error(UnknownId) otherwise.
ChromaticAdaptation idt_adaptation(const std::string& id);
const char* idt_adaptation_name(ChromaticAdaptation adaptation);

}  // namespace tristim

// tristim — camera quality as a colorimeter: how far a camera's spectral sensitivities are from
// the Luther condition (a linear combination of the CIE colour-matching functions).
//
// Sensitivity metamerism index (ISO 17321-1; the definition DxOMark and Imatest report):
//   SMI = 100 − 5.5 · mean ΔE*ab over the 18 chromatic patches (1–18) of the ColorChecker, with
//   the ISO 17321-1 (Ohta) reflectances, under the test illuminant (D65 by default), CIE 1931 2°
//   (summed on the camera's wavelength grid, as the camera is: simulate/virtual_camera.hpp),
//   after the best 3×3 matrix from the camera's RGB to XYZ. "Best" here: the white diffuser is
//   mapped to the illuminant's white exactly (white-point preserving, 6 free parameters) and the
//   mean ΔE*ab is minimised (NLopt BOBYQA from the white-point preserving least-squares matrix,
//   Finlayson & Drew 1997). A perfect (Luther) camera scores 100; SMI can be negative.
// μ-factor (Vora & Trussell 1993, "Measure of goodness of a set of color-scanning filters",
// J. Opt. Soc. Am. A 10(7)): with A the n×3 matrix of the CMFs and S the camera's n×3 sensitivities
// on the camera's wavelength grid, both weighted by the illuminant L (diagonal),
//   μ = trace(P_{LA} · P_{LS}) / 3,   P_X = X (XᵀX)⁻¹ Xᵀ the orthogonal projector onto span(X),
// 1 exactly when the camera's sensitivities span the CMFs' space, 0 when orthogonal to it.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"

namespace tristim {

struct CameraQuality {
  std::string camera;
  double smi = 0;             ///< 100 − 5.5 · mean_dE
  double mu_factor = 0;       ///< Vora–Trussell μ, 0..1
  double mean_dE = 0;         ///< mean ΔE*ab of the 18 patches after the matrix
  std::array<double, 9> matrix{};  ///< camera RGB (white diffuser's G = 1) -> XYZ (Y_white = 100), row-major
  std::vector<double> dE;     ///< per patch (18)
};

/// SMI and μ of one set of sensitivities (R, G, B columns) under `illuminant`.
/// Error(InvalidArgument) for sensitivities without three channels or with no response.
CameraQuality camera_quality(const SpectralData& sensitivities, const SpectralData& illuminant,
                             const std::string& camera = "");

/// The same with the matrix given (no optimisation): the ΔE*ab and SMI a fixed matrix reaches.
CameraQuality camera_quality_with_matrix(const SpectralData& sensitivities, const SpectralData& illuminant,
                                         const std::array<double, 9>& matrix, const std::string& camera = "");

/// The Vora–Trussell μ-factor alone (see header).
double mu_factor_VoraTrussell1993(const SpectralData& sensitivities, const SpectralData& illuminant);

/// Every built-in camera, best SMI first (ties: by name).
std::vector<CameraQuality> camera_quality_ranking(const SpectralData& illuminant);

/// The best-fit CMF combination for the plot: per camera channel c the least-squares fit
/// Σ_k a_kc · L·cmf_k ≈ L·s_c on the camera's grid, divided by L again; curves peak-normalised
/// together (the camera's largest value = 1).
struct LutherFit {
  std::vector<double> wavelengths;
  std::array<std::vector<double>, 3> camera, fit;
  std::array<double, 9> coefficients{};  ///< a_kc, row k = x̄, ȳ, z̄; column c = R, G, B
};
LutherFit luther_fit(const SpectralData& sensitivities, const SpectralData& illuminant);

/// The ISO 17321-1 ColorChecker reflectances (Ohta), 24 columns; SMI uses the first 18.
const SpectralData& iso17321_reflectances();

/// {"camera","smi","mu_factor","mean_dE"}: the CLI's row (the list also has matrix and dE).
json::Value camera_quality_json(const CameraQuality& q);

}  // namespace tristim

// Its field list (defined in smi.cpp): the CLI's rows and the wasm binding use it.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(CameraQuality);
}  // namespace tristim::fields

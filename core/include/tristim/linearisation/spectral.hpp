// Spectral characterisation (Shen, Xin, Yang & Lou 2008, eqs 26-28): reflectance from linearised
// camera responses by one N × 3 matrix,
//   r̂ = W û                       eq (26)
//   W = [r][û]⁺                    eq (27)   ([r]: N × Q measured reflectances, [û]: 3 × Q)
//   rms = sqrt((r − r̂)ᵀ(r − r̂) / N)  eq (28)
// û is the camera RGB through a fitted Linearisation (any row of the table); the reflectances
// are fractions on the training set's wavelength grid, which W keeps.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/json.hpp"
#include "tristim/linearisation/linearisation.hpp"

namespace tristim {

struct SpectralModel {
  Linearisation linearisation;      ///< stored values -> û
  std::vector<double> wavelengths;  ///< N, nm (the training reflectances' grid)
  Eigen::MatrixXd W;                ///< N × 3, eq (27)
  int training_patches = 0;
};

/// Fits W (eq 27) from stored camera RGB (Q × 3, rows named by `ids`) and measured reflectances
/// (a column per id). Errors: PatchMismatch (ids vs rows), MissingColumn (an id without a
/// reflectance), TooFewPatches (Q < 3), IllConditioned ([û] of rank < 3).
SpectralModel fit_spectral(const Linearisation& linearisation, const std::vector<std::string>& ids,
                           const PatchMatrix& camera_RGB, const SpectralData& reflectances);

/// Reflectance estimates r̂ = W û (eq 26) of stored camera RGB, one column per id, on
/// model.wavelengths.
SpectralData estimate_reflectances(const SpectralModel& model, const std::vector<std::string>& ids,
                                   const PatchMatrix& camera_RGB);

/// eq (28): RMS over wavelengths of r − r̂ (same length).
double spectral_rms(const std::vector<double>& measured, const std::vector<double>& estimated);

/// Per-patch accuracy of the estimates against measured reflectances (resampled onto the model's
/// grid): spectral RMS (eq 28) and CIEDE2000 between the XYZ of the two reflectances under any
/// illuminant and observer (Lab relative to that illuminant's white; the paper uses D65).
struct SpectralEvaluation {
  std::vector<std::string> ids;
  std::vector<double> rms, dE00;
  Summary rms_summary, dE00_summary;
};
SpectralEvaluation evaluate_spectral(const SpectralModel& model, const std::vector<std::string>& ids,
                                     const PatchMatrix& camera_RGB, const SpectralData& measured,
                                     const SpectralData& illuminant, Observer observer = Observer::CIE1931_2);

/// Per pixel: interleaved stored RGB (n_pixels × 3) -> reflectance bands (n_pixels × N, band
/// fastest), through the model's linearisation and W. No allocation besides a per-call copy of W.
void estimate_reflectance_image(const SpectralModel& model, const float* rgb, size_t n_pixels, float* bands);

/// Spectral CSV of estimates: "wavelength_nm,<id>,<id>,..." one row per wavelength (the format
/// read_spectral_csv / read_patch_file read back), values with 9 significant digits.
std::string spectral_csv(const SpectralData& spectra);

/// JSON: {"format": "tristim-spectral", "version": 1, "linearisation": {...},
/// "wavelengths": [...], "W": [[w_R, w_G, w_B] per wavelength], "training_patches": Q}
/// (17 significant digits: exact round trip). The reader refuses anything else (ProfileInvalid).
json::Value spectral_model_json(const SpectralModel& model);
SpectralModel spectral_model_from_json(const json::Value& value);

}  // namespace tristim

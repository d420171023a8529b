// Spectral characterisation (Shen, Xin, Yang & Lou 2008, eqs 26-28): reflectance from linearised
// camera responses by one N × 3 matrix,
//   r̂ = W û                       eq (26)
//   W = [r][û]⁺                    eq (27)   ([r]: N × Q measured reflectances, [û]: 3 × Q)
//   rms = sqrt((r − r̂)ᵀ(r − r̂) / N)  eq (28)
// û is the camera RGB through a fitted Linearisation (any row of the table); the reflectances
// are fractions on the training set's wavelength grid, which W keeps.
//
// Training set: the paper divides each chart into grey and non-grey patches (the ColorChecker's
// 6 greys, the DC's 13) and trains W on the non-grey ones ("the two sets containing nongray
// samples were used for the OECF estimation ... as well as colorimetric and spectral
// characterization", section "Experiments"); that is the default here. The greys are found by
// the same rule as the Shen2008 linearisation's (select_greys: given ids, or CIEDE2000 from the
// neutral of the same L* below a threshold, with the reflectances under D65); use_greys = 1
// trains on every patch.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"
#include "tristim/linearisation/linearisation.hpp"

namespace tristim {

struct SpectralModel {
  Linearisation linearisation;      ///< stored values -> û
  std::vector<double> wavelengths;  ///< N, nm (the training reflectances' grid)
  Eigen::MatrixXd W;                ///< N × 3, eq (27)
  int training_patches = 0;         ///< Q, the patches W was fitted on
  /// "non-grey" (the paper's: the greys left out) or "all" (use_greys = 1).
  std::string training_set = "all";
  std::vector<std::string> training_ids;  ///< the Q patches W was fitted on, in input order
  std::vector<std::string> greys;         ///< the grey patches found (left out unless "all")
  std::string grey_reason;                ///< how they were found (select_greys)
};

/// The spectral characterisation's row of the catalog: id "pseudo-inverse", the paper, and its
/// options — use_greys, grey, grey_threshold: the same names, meanings and defaults as the
/// Shen2008 linearisation's (grey_options()), so the CLI (--use-greys, --grey,
/// --grey-threshold), the page and --help read them from here.
const MethodInfo& spectral_method();

/// Fits W (eq 27) from stored camera RGB (Q × 3, rows named by `ids`) and measured reflectances
/// (a column per id), on the non-grey patches unless options say use_greys = 1 (`options`:
/// values for spectral_method()'s options, the rest default). Errors: PatchMismatch (ids vs
/// rows), MissingColumn (an id without a reflectance), UnknownId / InvalidArgument (options, a
/// given grey id), TooFewPatches (fewer than 3 training patches), IllConditioned ([û] of rank < 3).
SpectralModel fit_spectral(const Linearisation& linearisation, const std::vector<std::string>& ids,
                           const PatchMatrix& camera_RGB, const SpectralData& reflectances,
                           const MethodChoice& options = {});

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

/// JSON, written by SpectralModel's field list (below): {"format": "tristim-spectral", "version": 1,
/// "linearisation": {...}, "wavelengths": [...], "W": [[w_R, w_G, w_B] per wavelength],
/// "training_patches": Q, "training_set": "non-grey"|"all", "training_ids": [...], "greys": [...],
/// "grey_reason"} (17 significant digits: exact round trip). The reader refuses another format
/// or an unknown member (ProfileInvalid), another version (ProfileVersion); a model written before
/// training_set existed reads as trained on "all"; the "training" member `tristim spectral fit`
/// writes beside the model is known and not read.
json::Value spectral_model_json(const SpectralModel& model);
SpectralModel spectral_model_from_json(const json::Value& value);

}  // namespace tristim

// Their field lists (defined in spectral.cpp). A SpectralModel's object is its document (format
// and version first); a SpectralEvaluation's is what `tristim spectral apply --json` prints:
// {"summary": {"spectral_rms_mean", "_std", "_max", "dE00_mean", "_std", "_max"}, "patches":
// [{"patch", "spectral_rms", "dE00"}]} (only those figures of the two summaries are read back).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(SpectralModel);
TRISTIM_FIELDS_DECLARE(SpectralEvaluation);
/// A SpectralModel reads by its list and is then checked: wavelengths finite and increasing, W
/// one row of 3 per wavelength, training_set "all" or "non-grey" (the context's code).
template <>
struct Checks<SpectralModel> {
  static void check(SpectralModel& m, const Context& c, const std::string& p);
};
}  // namespace tristim::fields

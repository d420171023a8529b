// Phase I of Abed, Berns & Masaoka 2013 (Figure 6): the coefficients of a surface correction
// that map one measured reflectance set onto another measurement of the same patches in
// another geometry, by minimising the spectral RMS difference (bounded NLopt; the paper used
// Matlab's fmincon with the Saunderson coefficients in [0, 1]).
//
// Data: two SpectralData sets (reflectance factors, fractions in [0, 1.5]); patches are paired by
// column name after normalise_patch_id ("A01" = "A1"); both must hold the same patches
// (Error PatchMismatch otherwise) and cover the fitted wavelength range (Error
// WavelengthMismatch). The fit runs on the `measured` set's wavelengths inside the range; the
// target is interpolated onto them by the spectra.hpp rule when its grid differs.
// Colorimetry of the report: each set restricted to the range (held constant outside it, the
// spectra.hpp rule), integrated under `illuminant` and `observer`; CIELAB relative to the
// illuminant's white; ΔE00 of measured vs target (before) and corrected vs target (after).
#pragma once
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/methods.hpp"

namespace tristim {

struct SurfaceFitOptions {
  /// Fitted range in nm; both 0: the overlap of the two sets' ranges. A given range lies inside
  /// the range_min / range_max rows of surface_option_table() (options_table.hpp).
  double range_min = 0, range_max = 0;
  /// Illuminant of the CIELAB report (empty: D50) and observer.
  SpectralData illuminant;
  Observer observer = Observer::CIE1931_2;
  /// Fit separate coefficients at every wavelength (the choice's `spectral` option) instead of
  /// one set for all wavelengths (the paper's choice).
  bool per_wavelength = false;
  /// Saunderson only — which coefficients are free: "capture" (default: the instrument's
  /// k1, k2, k_ins stay as given, the paper's advice), "measurement", or a '+'-joined list of
  /// coefficient names. More than three free coefficients (e.g. "all") is refused with
  /// Error(IllPosed): eq (3) depends on the six only through the three of eq (4).
  std::string free = "capture";
  int max_evaluations = 3000;  ///< per start (and per wavelength)
};

/// Per-patch and summary report of a Phase I fit.
struct SurfaceFitResult {
  MethodChoice choice;              ///< the fitted correction (completed; reproduces it)
  std::vector<std::string> free;    ///< names of the coefficients that were fitted
  std::vector<double> wavelengths;  ///< the fitted grid (nm)
  std::vector<std::string> ids;     ///< paired patches, in the measured set's order
  SpectralData measured, corrected, target;  ///< on `wavelengths`, columns = ids
  std::vector<double> rms_before, rms_after;    ///< per patch: RMS over wavelengths
  std::vector<double> dE00_before, dE00_after;  ///< per patch
  double spectral_rms_before = 0, spectral_rms_after = 0;  ///< over every patch and wavelength
  Summary summary_dE00_before, summary_dE00_after;
  Vec3 white = Vec3::Zero();        ///< white of the CIELAB report (Y = 100)
  std::string illuminant;           ///< the report's illuminant: its name ("D50"; the CLI: as given)
  Observer observer = Observer::CIE1931_2;  ///< the report's observer
  int evaluations = 0;              ///< objective evaluations, all starts and wavelengths
  std::string status = "ok";        ///< "ok", "iteration_limit" or "at_bound"
  std::string message;              ///< what to look at when status is not "ok"
};

/// Fits `start.method` (its options are the start values and, for Saunderson, the fixed
/// coefficients) mapping `measured` onto `target`. Errors: UnknownId, InvalidArgument (bad
/// options, a range outside surface_option_table()'s rows, reflectance > 1.5), NegativeValue, PatchMismatch, DuplicateId, WavelengthMismatch,
/// IllPosed (too many free Saunderson coefficients), FitFailed (the optimiser failed).
SurfaceFitResult fit_surface(const MethodChoice& start, const SpectralData& measured, const SpectralData& target,
                             const SurfaceFitOptions& options = {});

/// The indices (row order) of the free coefficients of `method` for `free` (see
/// SurfaceFitOptions::free); every coefficient for the other rows. Error(IllPosed) as above.
std::vector<size_t> free_coefficients(const std::string& method, const std::string& free);

}  // namespace tristim

// The field list (io/fields.hpp; defined in surface/fields.cpp) of what `tristim surface fit --json`
// prints and the module's fitSurface gives: method, choice, surface (the choice as a --surface
// value), free, range_nm, wavelengths, illuminant, observer, status, message, evaluations,
// spectral_rms {before, after}, dE00 {before, after} (Summary's list), patches (one row per patch:
// patch, rms_before, rms_after, dE00_before, dE00_after), then measured, corrected and target
// (spectra: wavelengths, names, values, linear) when the result holds them — the CLI prints the
// figures and leaves the spectra out, the page draws them. Written only (derived members).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(SurfaceFitResult);
}  // namespace tristim::fields

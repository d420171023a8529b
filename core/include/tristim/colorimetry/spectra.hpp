// Spectral distributions on arbitrary wavelength grids, the built-in CIE tables (colour-matching
// functions, illuminants, the daylight basis) and spectrum -> XYZ.
//
// Interpolation rule (CIE 15:2004 §7.2.1.1 recommends Sprague for uniformly spaced data):
//   * uniformly spaced data with at least 6 samples: Sprague (1880) quintic interpolation, the
//     boundary handled as CIE 167:2005 / colour-science's SpragueInterpolator (two extra points
//     per end from the 6 nearest samples with the 1/209 coefficients);
//   * anything else (non-uniform, fewer than 6 samples): piecewise linear;
//   * data flagged `linear` (the built-in CIE illuminants and the daylight basis): linear, as CIE
//     15:2004 §7.2.1.1 recommends for the D illuminants (their 5 nm values are themselves linear
//     interpolations of 10 nm data) and as colour-science does for its illuminants;
//   * outside the measured range: constant extrapolation (the first/last value is held), as
//     colour-science's `align` does by default.
// Integration rule (colour-science's `sd_to_XYZ_integration` with the 1 nm CMFs): reflectance and
// illuminant are aligned to the CMF grid (360-830 nm, 1 nm) by the rule above, then
//   X = k Σ R(λ) S(λ) x̄(λ),  k = 100 / Σ S(λ) ȳ(λ)      (CIE 15:2004 eqs 7.1-7.2, Δλ cancels)
// so the perfect diffuser (R = 1) has Y = 100.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"

namespace tristim {

/// One or more spectral distributions sharing a wavelength grid.
/// wavelengths: nm, strictly increasing. values[k][i] = column k at wavelengths[i].
/// Reflectances are fractions (0..1); illuminants and sensitivities are relative.
struct SpectralData {
  std::vector<double> wavelengths;
  std::vector<std::string> names;           // one per column
  std::vector<std::vector<double>> values;  // one vector per column, each wavelengths.size() long
  bool linear = false;                      // interpolate linearly even if uniformly spaced
  size_t size() const { return values.size(); }
  /// Column by name (exact match); Error(MissingColumn) if absent.
  const std::vector<double>& column(std::string_view name) const;
};

/// True when the grid is uniformly spaced (relative tolerance 1e-9 of the step).
bool is_uniform(const std::vector<double>& wavelengths);

/// Values of one distribution at `new_wavelengths` by the rule above (Sprague / linear, constant
/// extrapolation). Throws Error(NonMonotonic) if `wavelengths` is not strictly increasing,
/// Error(InvalidArgument) if sizes differ or the distribution is empty.
std::vector<double> interpolate_spectrum(const std::vector<double>& wavelengths, const std::vector<double>& values,
                                         const std::vector<double>& new_wavelengths, bool linear = false);
/// Every column of `data` re-sampled on `new_wavelengths`.
SpectralData align_spectra(const SpectralData& data, const std::vector<double>& new_wavelengths);

/// Weights on `new_wavelengths` pulled back onto a distribution's own grid `wavelengths` (the
/// ASTM E308 idea of weighting factors on the measurement interval). For every v on `wavelengths`,
///   Σ_i weights[c][i] · interpolate_spectrum(wavelengths, v, new_wavelengths, linear)[i]
///     = Σ_t pulled.weights[c][t] · v[pulled.nodes[t]]
/// in exact arithmetic: the interpolation rule above (Sprague or linear, constant extrapolation)
/// is linear in v, v ↦ A v, so wᵀ(A v) = (Aᵀ w)ᵀ v; Aᵀ w is built row by row of A, never A itself.
/// In floating point the two differ by summation order only (a few ulps of Σ|w||v|).
/// `nodes` lists the samples the interpolation reads, ascending; a sample it never reads (outside
/// every Sprague window) is left out, so a NaN there is ignored as interpolate_spectrum ignores it.
/// x, y, z: the three channels' weights, each new_wavelengths.size() long. Throws as
/// interpolate_spectrum for `wavelengths` (empty, not strictly increasing), Error(InvalidArgument)
/// for a weight vector of the wrong length.
struct PulledBackWeights {
  std::vector<size_t> nodes;    // indices into wavelengths, ascending
  std::vector<double> weights;  // node-major: weights[3 t + c] for node t, channel c
  size_t samples = 0;           // wavelengths.size()
  /// (Σ_t weights[3 t + c] · v[nodes[t]]) for c = 0, 1, 2, each summed over t in order;
  /// Error(InvalidArgument) unless v has `samples` values.
  Vec3 dot(const std::vector<double>& v) const;
};
PulledBackWeights pull_back_weights(const std::vector<double>& wavelengths, bool linear,
                                    const std::vector<double>& new_wavelengths, const std::vector<double>& x,
                                    const std::vector<double>& y, const std::vector<double>& z);

/// Sprague (1880) interpolation of uniformly spaced samples (exposed for tests): y at x, with
/// x0 = first wavelength, step h. Needs >= 6 samples and x0 <= x <= x_last.
double sprague_interpolate(const std::vector<double>& y, double x0, double h, double x);

/// Evenly spaced grid start, start+step, ..., end (inclusive).
std::vector<double> wavelength_grid(double start, double end, double step);

// ------------------------------------------------------------------ observers

enum class Observer { CIE1931_2, CIE1964_10 };
/// "1931", "2", "CIE 1931 2 Degree Standard Observer" -> CIE1931_2; "1964", "10" -> CIE1964_10.
/// Error(UnknownId) otherwise.
Observer parse_observer(std::string_view id);
const char* observer_name(Observer observer);  // "1931" or "1964"
/// The observers with a name for pickers: {"1931", "CIE 1931 2°"}, {"1964", "CIE 1964 10°"}.
struct ObserverInfo {
  std::string id, name;
};
std::vector<ObserverInfo> list_observers();

/// The CIE colour-matching functions x̄ ȳ z̄ at 1 nm, 360-830 nm (columns "xbar","ybar","zbar").
const SpectralData& cmfs(Observer observer);

/// Chromaticity of the monochromatic stimuli (the spectral locus), 360-830 nm at 1 nm.
struct SpectralLocus {
  std::vector<double> wavelengths, x, y;
};
SpectralLocus spectral_locus(Observer observer);

// ------------------------------------------------------------------ illuminants

/// Ids of the built-in illuminants: A, D50, D55, D65, D75, E, F2, F11. (Any "D<CCT>", e.g.
/// "D4000", also works: CIE daylight at that correlated colour temperature.)
std::vector<std::string> illuminant_ids();
/// The same with a name for pickers ("F11 (TL84-type fluorescent)").
struct IlluminantInfo {
  std::string id, name;
};
std::vector<IlluminantInfo> list_illuminants();

/// Relative SPD of a built-in illuminant (one column named after it), as tabulated; or, for an
/// id "D<T>" with 4000 <= T <= 25000 that is not tabulated, daylight_spd(T). Error(UnknownId).
SpectralData illuminant_spd(std::string_view id);

/// CIE daylight at correlated colour temperature cct (K, 4000..25000) from the S0, S1, S2 basis
/// (CIE 15:2004 eqs 3.3-3.5; M1, M2 rounded to 3 decimals as the standard prescribes for the
/// tabulated D illuminants), 300-830 nm at 5 nm, normalised to 100 at 560 nm.
/// The nominal D65 is cct = 6500 * 1.4388 / 1.4380 (≈ 6504 K); likewise D50, D55, D75.
SpectralData daylight_spd(double cct);

// ------------------------------------------------------------------ spectrum -> XYZ

/// XYZ of each column of `reflectances` (fractions) under `illuminant` (first column used) for
/// `observer`, by the integration rule at the top of this file; the perfect diffuser has Y = 100.
/// With `white_XYZ`, also the illuminant's white (illuminant_white_XYZ's value; the illuminant is
/// weighted once for both).
std::vector<Vec3> reflectances_to_XYZ(const SpectralData& reflectances, const SpectralData& illuminant,
                                      Observer observer = Observer::CIE1931_2, Vec3* white_XYZ = nullptr);
/// One reflectance.
Vec3 sd_to_XYZ(const std::vector<double>& wavelengths, const std::vector<double>& reflectance,
               const SpectralData& illuminant, Observer observer = Observer::CIE1931_2);
/// XYZ of the perfect diffuser under `illuminant`: the white point, Y = 100.
Vec3 illuminant_white_XYZ(const SpectralData& illuminant, Observer observer = Observer::CIE1931_2);

/// A reflectance table given in percent (any value > 2) is divided by 100; fractions are
/// returned unchanged. Returns true if it scaled.
bool reflectance_to_fraction(SpectralData& reflectances);

}  // namespace tristim

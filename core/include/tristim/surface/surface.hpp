// Surface correction of the reference: the chart's reflectances as measured by an instrument in
// one geometry, converted to what the camera sees in the capture geometry (Abed, Berns &
// Masaoka 2013). One table row per method; the recipe's `surface` stage names a row by id and
// gives its coefficients as options, so a MethodChoice alone reproduces a correction.
//
// Rows (coefficients in this order; R = reflectance factor, a fraction):
//   none           R' = R
//   scaler         R' = μR                                     (the paper's "scaler", Phase I)
//   offset         R' = R + ρ                                  (the paper's "offset", Phase I)
//   scaler-offset  R' = μR + ρ                                 eq (5), Appendix B
//   saunderson     R' = eq (3) with the measurement geometry (k1, k2, k_ins) and the capture
//                  geometry (k1_capture, k2_capture, k_ins_capture), applied as eq (4) with the
//                  Appendix A mapping (saunderson.hpp)
// Coefficients are wavelength-independent (the paper's choice) unless the text option
// `spectral` is given: a ';'-separated list of entries "λ/c1/c2/..." (nm, then the row's
// coefficients in the order above), e.g. "400/1.02/-0.01;410/1.01/-0.012". Between listed
// wavelengths the coefficients are interpolated linearly, outside they are held constant; when
// `spectral` is set it replaces the scalar options.
// Every row but `none` also has the choice option `fit`: "fixed" (the default: the coefficients
// are applied as given) or "joint" (Phase II in the fit step: characterise() fits the coefficients
// jointly with a 3×3 anchored to the chart's white patch, joint.hpp, starting from the given
// values; correct_surface itself always applies the values as given).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/methods.hpp"

namespace tristim {

/// One row of the surface-correction table.
struct SurfaceMethod {
  MethodInfo info;
  /// Reflectances (fractions) -> corrected reflectances, with the (completed) options.
  SpectralData (*apply)(const SpectralData& reflectances, const MethodChoice& choice);
  /// Names of the row's coefficient options, in the order of eq (3)/(5) and of `spectral`.
  std::vector<std::string> coefficients;
  /// The correction as the paper writes it ("R' = μR + ρ, eq (5)"); empty for `none`.
  std::string equation;
  /// For a row whose coefficients are Saunderson geometries (saunderson.hpp): per role
  /// ("measurement", "capture", as SaundersonPreset::role names them) the option each field of a
  /// SaundersonGeometry sets, e.g. capture: {k1: "k1_capture", k2: "k2_capture", k_ins:
  /// "k_ins_capture"}; so a preset fills a choice without the caller knowing the option names.
  /// Empty for the other rows.
  std::map<std::string, std::map<std::string, std::string>> geometry;
};

/// Every surface correction, in a stable order (`none` first).
const std::vector<SurfaceMethod>& surface_table();
/// A row as the page's picker lists it: the MethodInfo's fields, its coefficient names, equation
/// and (Saunderson) the option each geometry field sets per role.
struct SurfaceListing {
  std::string id, label, reference;
  std::vector<OptionSpec> options;
  std::vector<std::string> coefficients;
  std::string equation;
  std::map<std::string, std::map<std::string, std::string>> geometry;
};
/// surface_table() as listings, in its order.
std::vector<SurfaceListing> surface_listing();
/// A row by id; Error(UnknownId) naming the id otherwise.
const SurfaceMethod& surface_method(const std::string& id);
/// Applies the chosen correction (options checked and completed from the table). The input
/// must hold reflectance factors in [0, 1.5] (check_reflectances). The output is not clipped:
/// an offset may take a dark patch slightly below zero.
SpectralData correct_surface(const MethodChoice& choice, const SpectralData& reflectances);

/// Error(NegativeValue) for a value < 0, Error(InvalidArgument) for one > 1.5 (percent data
/// should be divided by 100 first) or not finite; `what` names the set in the message.
void check_reflectances(const SpectralData& reflectances, const std::string& what);

/// The coefficients of a (completed) choice at each of `wavelengths`: one vector per
/// wavelength, the row's coefficients in order. Error(InvalidArgument) for a malformed
/// `spectral` text or a value outside the option's bounds.
std::vector<std::vector<double>> surface_coefficients(const MethodChoice& choice,
                                                      const std::vector<double>& wavelengths);
/// The `spectral` text for per-wavelength coefficients (inverse of the parsing above; numbers
/// with 17 significant digits so the text reproduces them exactly).
std::string spectral_coefficients_text(const std::vector<double>& wavelengths,
                                       const std::vector<std::vector<double>>& coefficients);
/// A choice of method `id` with the given scalar coefficients (row order), other options default.
MethodChoice surface_choice(const std::string& id, const std::vector<double>& coefficients);

/// One reflectance through row `id` with its coefficients (row order). For saunderson this is
/// eq (3); apply_surface uses the eq (4) form, equal to it to rounding.
double surface_value(const std::string& id, const std::vector<double>& coefficients, double R);

/// "id:name=value,..." that parse_choice reads back to the same choice (the CLI's --surface);
/// numbers with 17 significant digits.
std::string surface_choice_text(const MethodChoice& choice);

}  // namespace tristim

// Internal to core/src/linearisation: the rows of the linearisation table, one file per family,
// and the helpers they share. Not installed; include only from core/src/linearisation/*.cpp.
#pragma once
#include <string>
#include <vector>

#include "tristim/linearisation/linearisation.hpp"

namespace tristim::linearisation_detail {

// --- rows, in table order (linearisation.cpp assembles them) ------------------------------
LinearisationMethod row_identity();
LinearisationMethod row_gamma();
LinearisationMethod row_sRGB();
/// grey-polynomial, grey-log-polynomial, colour-polynomial, colour-log-polynomial.
std::vector<LinearisationMethod> rows_polynomial();
// Guarnera2018 (absolute colorimetry) is declared in tristim/linearisation/guarnera2018.hpp
// (linearisation_row_Guarnera2018, guarnera2018.cpp); it sits between the polynomial rows and Shen2008.
LinearisationMethod row_Shen2008();

// --- shared helpers ----------------------------------------------------------------------

/// data.full_scale, or the largest finite value of camera_RGB when it is 0 (at least 1e-300).
double full_scale_of(const LinearisationData& data);
/// Checks the shape of the data (ids vs rows: PatchMismatch; NaN/Inf: NonFinite).
void check_data(const LinearisationData& data);

/// The rows of `candidates` usable for fitting channel c: finite, and not clipped when the
/// encoding's full scale is known (x <= 0 or x >= 1 - 0.5/255 count as clipped). Clipped rows
/// are named in `l.message`.
std::vector<int> usable_rows(const LinearisationData& data, const std::vector<int>& candidates, int channel,
                             double full_scale, Linearisation& l);

/// The linear value of each grey row (rows × 3, other rows 0): the mean reflectance over
/// 400-700 nm when reflectances are known (Shen 2008 Fig 5), else Y / Y_white of the reference.
PatchMatrix grey_values(const LinearisationData& data, const std::vector<int>& rows);

/// A struct of this folder read from JSON by its field list (Error(ProfileInvalid), the message
/// starting with `prefix`: "linearisation: ").
template <class T>
T read_fields(const json::Value& o, const char* prefix) {
  T out;
  fields::read(o, out, fields::Context{ErrorCode::ProfileInvalid, prefix});
  return out;
}

/// Appends a warning to l.message ("; "-separated).
void add_warning(Linearisation& l, const std::string& warning);

/// Polynomial curve in x = value / full_scale (coefficients ascending).
double apply_polynomial(const Linearisation& l, int channel, double value);
double inverse_polynomial(const Linearisation& l, int channel, double linear);
/// exp(P(ln x)) for x > 0, 0 otherwise (OpenCV ccm's LogPolyfit).
double apply_log_polynomial(const Linearisation& l, int channel, double value);
double inverse_log_polynomial(const Linearisation& l, int channel, double linear);

/// Sets l.monotonic / adds a warning when a channel's curve is not increasing over its domain.
void check_monotonic(Linearisation& l, double (*apply)(const Linearisation&, int, double));

/// Fills l.extrapolated with every row and channel of `data` whose x lies outside l.domain (set
/// by record_fit) and adds one warning naming them, by how much relative to the range's end.
void check_extrapolation(Linearisation& l, const LinearisationData& data);

/// Fills l.domain[c] from the x of the fitted rows, and l.fitted (union over channels, in row
/// order) from per-channel row lists.
void record_fit(Linearisation& l, const LinearisationData& data, const std::array<std::vector<int>, 3>& rows,
                double full_scale);

}  // namespace tristim::linearisation_detail

// One surface correction at one wavelength, prepared once for many reflectances (internal to
// core/src/surface): the rows of surface.hpp as R' = a·R + b or, for Saunderson, eq (4) with the
// Appendix A mapping.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/surface/saunderson.hpp"

namespace tristim::surface_detail {

struct PointCorrection {
  enum Kind { None, Scaler, Offset, ScalerOffset, Saunderson } kind = None;
  double a = 1, b = 0;  // scaler / offset / scaler-offset: R' = a R + b (eq 5)
  ThreeParameter t;     // saunderson: eq (4)
  double value(double R) const { return kind == Saunderson ? t.apply(R) : a * R + b; }
};

/// The kind of a row id; Error(UnknownId) otherwise.
PointCorrection::Kind correction_kind(const std::string& id);
/// Coefficients in row order -> prepared correction; Error(IllPosed) for singular Saunderson
/// coefficients (three_parameter_Abed2013).
PointCorrection prepare_correction(PointCorrection::Kind kind, const std::vector<double>& c);

/// The spectra.hpp integration rule as a matrix: for reflectances sampled on `wavelengths`
/// (interpolated by the rule `linear` selects), XYZ row = R row · T, T being L × 3. Exact: the
/// alignment (Sprague / linear, constant extrapolation) and the sum are linear in the samples,
/// so T is the XYZ of the L unit spectra.
Eigen::MatrixXd integration_matrix(const std::vector<double>& wavelengths, bool linear, const SpectralData& illuminant,
                                   Observer observer);

/// Start points of a Saunderson fit (full coefficient vectors, row order), for the free block
/// `free` ({3,4,5} capture or {0,1,2} measurement, others: `base` alone): `base`; the
/// scaler-offset optimum (mu, rho) read back through Appendix B (k2 = k2c; μ = (1 − k1c)/(1 − k1),
/// ρ = k_ins,c·k1c − μ·k_ins·k1), so the fit is never worse than scaler-offset when that point
/// lies inside the bounds; and `base` with the free specular term at its other end.
std::vector<std::vector<double>> saunderson_starts(const std::vector<double>& base, const std::vector<size_t>& free,
                                                   double mu, double rho);

}  // namespace tristim::surface_detail

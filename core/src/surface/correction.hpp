// One surface correction at one wavelength, prepared once for many reflectances (internal to
// core/src/surface): the rows of surface.hpp as R' = a·R + b or, for Saunderson, eq (4) with the
// Appendix A mapping.
#pragma once
#include <string>
#include <vector>

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

}  // namespace tristim::surface_detail

// Surface correction of the reference: the chart's reflectances as measured by an instrument in
// one geometry, converted to what the camera sees in the capture geometry (Abed, Berns &
// Masaoka 2013). One table row per method; the recipe's `surface` stage names a row by id and
// gives its coefficients as options. `none` leaves the reflectances as measured.
#pragma once
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
};

/// Every surface correction, in a stable order (`none` first).
const std::vector<SurfaceMethod>& surface_table();
/// A row by id; Error(UnknownId) naming the id otherwise.
const SurfaceMethod& surface_method(const std::string& id);
/// Applies the chosen correction (options checked and completed from the table).
SpectralData correct_surface(const MethodChoice& choice, const SpectralData& reflectances);

}  // namespace tristim

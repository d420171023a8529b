// Abed, Berns & Masaoka 2013 "corrected 3×3" as a characterisation model (fit.hpp,
// fit_corrected_3x3): Appendix C steps 4-7 on the user's own patches, through the surface module's
// fit_corrected_3x3_Abed2013 (eqs 26-28), with the summary every fit carries.
#include <cmath>
#include <string>

#include "tristim/characterisation/fit.hpp"
#include "tristim/error.hpp"
#include "tristim/surface/joint.hpp"

namespace tristim {

FitResult fit_corrected_3x3(const PatchMatrix& rgb, const PatchMatrix& xyz, const FitOptions& options) {
  if (options.objective != Objective::LeastSquares)
    throw Error(ErrorCode::InvalidArgument, std::string("model '") + kCorrected3x3 +
                                                "' is closed form (Abed 2013 eqs 26-28): objective ls only, not " +
                                                objective_id(options.objective));
  if (!(options.white_RGB.squaredNorm() > 0) || !(options.white_XYZ.squaredNorm() > 0))
    throw Error(ErrorCode::InvalidArgument, std::string("model '") + kCorrected3x3 +
                                                "' needs the white reference's camera RGB and XYZ for mu (Abed 2013 eq 27): "
                                                "name the white patch (--white <id>, the recipe's white_patch)");
  // Step 4, eq (26): the least-squares 3×4 — its summary (condition, status) is the fit's.
  FitOptions o;
  o.warn_condition = options.warn_condition;
  o.max_condition = options.max_condition;
  const FitResult affine = fit("matrix-3x4", rgb, xyz, o);
  // Steps 5-7: M' (the offset column dropped), μ (eq 27), M_cr = μ·M' (eq 28).
  const CorrectedMatrix m = fit_corrected_3x3_Abed2013(rgb, xyz, options.white_RGB, options.white_XYZ);
  FitResult r;
  r.model.id = kCorrected3x3;
  r.model.coefficients = m.matrix;
  r.objective = Objective::LeastSquares;
  r.status = affine.status;
  r.message = affine.message;
  r.condition_number = affine.condition_number;
  r.mu = m.mu;
  r.fitted = predict(r.model, rgb);
  r.residuals = r.fitted - xyz;
  r.objective_value = std::sqrt(r.residuals.squaredNorm() / (3.0 * static_cast<double>(rgb.rows())));
  r.start_objective_value = r.objective_value;
  return r;
}

}  // namespace tristim

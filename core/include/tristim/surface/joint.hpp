// Phase II of Abed, Berns & Masaoka 2013: the surface correction fitted jointly with the camera's
// 3×3 matrix (the Figure 3 loop), and the "corrected 3×3" of eqs (6)-(13) / Appendix C.
//
// Figure 3 loop: instrument reflectances R_m -> corrected R_m,c (eq 3 or eq 5, coefficients θ)
// -> XYZ_m,c (integrated under the illuminant) -> least-squares 3×3 matrix M from camera RGB
// -> ΔE_xyz between M·RGB and XYZ_m,c -> minimised over θ (bounded NLopt), the instrument's
// coefficients fixed (all six Saunderson coefficients free is ill-posed, Error IllPosed).
//
// Anchoring rule (the scale degeneracy). ΔE_xyz falls with the size of the reference: a
// correction that shrinks every reflectance (μ -> 0, or k1' -> 1) would let the matrix shrink
// with it and drive the error to zero. Both the instrument and the camera measure reflectance
// factors relative to a Lambertian white reference (pressed PTFE), which reads its own
// reflectance R_w in every geometry. So the matrix is tied to that white: M·RGB_w = R_w·XYZ_il
// exactly (RGB_w: the camera RGB of the white reference in the capture geometry; XYZ_il: the
// illuminant's white, Y = 100; the same white as eq (12)). With the camera's scale fixed by the
// white, a correction that shrinks or inflates the reference is no longer followed by the
// matrix and raises the error instead. (`anchor_white = false` drops the constraint, for the test
// that shows the degeneracy.)
//
// Units: camera RGB linear (any scale); XYZ with the perfect diffuser at Y = 100; ΔE_xyz is the
// Euclidean XYZ distance in those units.
#pragma once
#include <string>
#include <vector>

#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/methods.hpp"

namespace tristim {

struct JointFitOptions {
  SpectralData illuminant;                 ///< empty: D50
  Observer observer = Observer::CIE1931_2;
  Vec3 white_RGB = Vec3::Zero();           ///< camera RGB of the white reference (required when anchored)
  double white_reflectance = 1.0;          ///< R_w of the white reference (pressed PTFE ≈ 0.99)
  bool anchor_white = true;                ///< the rule above; false only to demonstrate the degeneracy
  std::string free = "capture";            ///< Saunderson: as SurfaceFitOptions::free
  int max_evaluations = 3000;              ///< per start
};

struct JointFitResult {
  MethodChoice choice;              ///< the fitted correction (completed)
  std::vector<std::string> free;    ///< the coefficients that were fitted
  Mat3 matrix = Mat3::Identity();   ///< XYZ = matrix · RGB
  PatchMatrix reference_XYZ;        ///< the instrument's XYZ (uncorrected), N × 3
  PatchMatrix corrected_XYZ;        ///< XYZ of the corrected reflectances, N × 3
  PatchMatrix fitted_XYZ;           ///< matrix · RGB, N × 3
  double dE_xyz_rms_start = 0;      ///< RMS ΔE_xyz at the start coefficients
  double dE_xyz_rms = 0;            ///< RMS over patches of |matrix·RGB − XYZ_m,c|
  int evaluations = 0;
  std::string status = "ok";        ///< "ok", "iteration_limit" or "at_bound"
  std::string message;
};

/// The Figure 3 loop for `start.method` (scaler, offset, scaler-offset, saunderson, or none:
/// the anchored 3×3 alone). camera_RGB: N × 3, row i = column i of `reflectances` (the
/// instrument's reflectance factors, fractions in [0, 1.5]). Errors: PatchMismatch (N differs),
/// TooFewPatches (N < 3), NegativeValue / InvalidArgument (reflectances), InvalidArgument (no
/// white RGB when anchored, non-finite input), IllPosed (too many free Saunderson
/// coefficients, or a white RGB of zero), IllConditioned (collinear RGB).
JointFitResult fit_surface_joint_Abed2013(const MethodChoice& start, const PatchMatrix& camera_RGB,
                                          const SpectralData& reflectances, const JointFitOptions& options);

/// The "corrected 3×3" (eqs 6-13, Appendix C steps 4-7).
struct CorrectedMatrix {
  Eigen::Matrix<double, 3, 4> matrix_3x4;  ///< eq (26): [M' | offset], XYZ = M'·RGB + offset
  Mat3 matrix_prime;                        ///< M', the 3×4 without its offset column (step 5)
  double mu = 1;                            ///< eq (12)/(27)
  Mat3 matrix;                              ///< eq (13)/(28): M_cr = μ·M'
};
/// camera_RGB, reference_XYZ: N × 3 (N >= 4); white_RGB: the white reference's camera RGB;
/// white_XYZ: its XYZ (the illuminant's, times its reflectance). μ = (M'·RGB_w)⁺·XYZ_w, the
/// pseudo-inverse of the 3 × 1 vector M'·RGB_w: (vᵀ·XYZ_w)/(vᵀv). Errors: PatchMismatch,
/// TooFewPatches, IllConditioned, IllPosed (M'·RGB_w = 0).
CorrectedMatrix fit_corrected_3x3_Abed2013(const PatchMatrix& camera_RGB, const PatchMatrix& reference_XYZ,
                                           const Vec3& white_RGB, const Vec3& white_XYZ);

}  // namespace tristim

// The field list (io/fields.hpp; defined in surface/fields.cpp) of what `tristim surface joint
// --json` prints and the module's fitSurfaceJoint gives: choice, surface (the choice as a --surface
// value), matrix (9 numbers, row-major), dE_xyz_rms_start, dE_xyz_rms, status, message,
// evaluations. Written only (surface is derived from choice).
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(JointFitResult);
}  // namespace tristim::fields

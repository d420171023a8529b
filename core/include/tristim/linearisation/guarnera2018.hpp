// Guarnera, Bianco & Schettini (2018), "Turning a Digital Camera into an Absolute 2D
// Tele-Colorimeter", section 3.1: the power-law inverse OECF per channel,
//   eq (8):  F⁻¹(R') = R'^(1/k3) / k2 − k1
// applied to values normalised by eq (7),
//   R' = (R − n)·A_G / ((S − n)·A_R) · f(r),   G' = (G − n)/(S − n) · f(r),   B' likewise with A_B,
// and fitted to equal-tristimulus stimuli of known luminance Y (cd/m²).
//
// Exposure scaling (reciprocity, section 3.1): the sensor responds to the exposure
// H = Y·ε with ε = t/N² (t exposure time in s, N the f-number; times ISO/ISO_ref when the ISO
// differs). F⁻¹ here returns H, so Y = F⁻¹(R')/ε and one curve serves every {t, N}; for a single
// {t, N} (ε = 1) this is the paper's per-exposure curve in cd/m² directly.
//
// The `Guarnera2018` row of the linearisation table (linearisation.hpp) fits one {t, N} from a
// patch table (camera_RGB in DN, reference_XYZ's Y in cd/m²); the multi-exposure fit with the
// reciprocity check is absolute/luminance.hpp.
#pragma once
#include <string>
#include <vector>

#include "tristim/linearisation/linearisation.hpp"

namespace tristim {

/// One channel's eq (8) coefficients.
struct InverseOecf {
  double k1 = 0;  ///< offset, in exposure units (noise sources other than the floor n)
  double k2 = 1;  ///< absolute scale (normalised value per unit exposure, before the power)
  double k3 = 1;  ///< residual non-linearity (gamma); 1 = linear
  /// eq (8): F⁻¹(R') = R'^(1/k3)/k2 − k1. For R' < 0 (noise below the floor) the root keeps
  /// the sign, −|R'|^(1/k3), so the curve stays continuous and monotonic.
  double operator()(double normalised) const;
  /// The OECF itself, R' = (k2·(H + k1))^k3 (signed power), the inverse of operator().
  double forward(double exposure) const;
};

/// Eq (7) for one value: (value − n)/(S − n) · area_ratio · falloff, with area_ratio = A_G/A_c
/// (1 for G). value, n and S in the same units (black-subtracted DN for RAW).
inline double normalise_Guarnera2018(double value, double noise_floor, double saturation,
                                     double area_ratio = 1, double falloff = 1) {
  return (value - noise_floor) / (saturation - noise_floor) * area_ratio * falloff;  // eq (7)
}

/// One training sample of one channel.
struct OecfSample {
  double normalised = 0;  ///< R' (eq 7)
  double exposure = 1;    ///< ε = t/N² (·ISO/ISO_ref), 1 for a single {t, N}
  double Y = 0;           ///< known luminance of the equal-tristimulus stimulus, cd/m²
};

struct OecfFitOptions {
  /// Residuals are relative: (Ŷ − Y)/(Y + y_floor·max Y), so stimuli across decades count
  /// alike while the dark end (Y → 0) is not divided by zero.
  double y_floor = 0.01;
  bool fit_k1 = true;   ///< false: k1 = 0
  bool fit_k3 = true;   ///< false: k3 = 1 (linear sensor)
  double k3_min = 0.25, k3_max = 4;  ///< bounds of k3 (NLopt bounded search)
  double xtol_rel = 1e-10;
  int max_evaluations = 4000;
};

struct OecfFit {
  InverseOecf curve;
  int samples = 0;
  double rms_relative = 0;  ///< RMS of the relative residuals (see y_floor)
  double max_relative = 0;  ///< largest |relative residual|
  double r_squared = 0;     ///< 1 − SS_res/SS_tot of Ŷ against Y (cd/m²)
  int evaluations = 0;      ///< NLopt objective evaluations
  std::string message;      ///< empty when fine
};

/// Fits eq (8) to the samples of one channel: NLopt BOBYQA on (k1, ln k2, k3) within bounds
/// (k3 in [k3_min, k3_max], ln k2 within ±8 of the start, |k1| ≤ the largest exposure),
/// started from the linear least-squares fit H = R'/k2 − k1 (k3 = 1), minimising the sum of
/// squared relative residuals of Y = F⁻¹(R')/ε.
/// Errors: TooFewPatches (fewer than 3 samples), NonFinite, NegativeValue (Y < 0 or ε ≤ 0),
/// IllPosed (every R' equal, or no stimulus with Y > 0).
OecfFit fit_inverse_oecf_Guarnera2018(const std::vector<OecfSample>& samples,
                                      const OecfFitOptions& options = {});

/// The `Guarnera2018` row of the linearisation table. Options (MethodChoice parameters):
/// noise_floor n (DN), saturation S (DN; 0: the data's full scale, else its maximum),
/// area_R/area_G/area_B (A_c of eq 7, any common scale), exposure_s t, f_number N, iso
/// (0: no ISO scaling; else ε is multiplied by iso/100), y_floor, fit_k3.
/// fit: camera_RGB (DN, one {t, N}) and reference_XYZ's Y (cd/m²); saturated rows (≥ S) are
/// skipped. Coefficients per channel: {k1, k2, k3}. apply: DN → eq (7) → eq (8) → Y in cd/m².
LinearisationMethod linearisation_row_Guarnera2018();

}  // namespace tristim

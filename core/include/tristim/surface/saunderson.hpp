// The Saunderson surface correction and its reduced forms (Abed, Berns & Masaoka 2013, eqs 1-5,
// Appendices A and B). Pure functions of one reflectance factor (a fraction) at one wavelength.
//
// Naming by role, not by prime. A *geometry* is the triple (k1, k2, k_ins) of eqs (1)-(2):
//   k1     fraction of the light incident from outside reflected at the surface (Fresnel; 0.040 for
//          parallel light at normal incidence, 0.092 for diffuse light, refractive index ≈ 1.5);
//   k2     fraction of the light incident from inside reflected at the surface (0.4-0.6 for paints);
//   k_ins  fraction of the externally reflected (specular) light the detector receives
//          (1: specular included, e.g. d:8 SCI; 0: specular excluded, e.g. 45:0, d:8 SCE).
// The *measurement* geometry is the instrument's (the reflectances a chart comes with), the
// *capture* geometry the camera's. The conversion of eq (3) is eq (2) with the measurement
// geometry (measured -> internal reflectance) followed by eq (1) with the capture geometry
// (internal -> reflectance the camera sees), as Figures 2 and 3 describe.
//
// Errata. In eqs (3) and (14)-(25) as printed the primed coefficients are the ones eq (2)
// inverts (the measurement) although the sentence after eq (3) calls them the camera's; eq (3)
// also prints k_ins·k1 inside the denominator (eq (14) has it outside, as it must be), eq (14)
// prints R_m(k2 − k2') where the derivation gives the opposite sign, eq (18) prints k_ins'·k1·k2
// for k_ins'·k1'·k2, and the α, γ of eq (21) carry sign slips. The closed forms below are derived
// from eqs (1)-(2) and tests/core/surface check every one numerically against them.
#pragma once
#include <string>
#include <vector>

namespace tristim {

/// (k1, k2, k_ins) of one measurement or capture geometry (eqs 1-2). Physical values lie in
/// [0, 1]; k1 < 1 and k2 < 1 keep the equations finite.
struct SaundersonGeometry {
  double k1 = 0.04, k2 = 0.6, k_ins = 0;
};

/// Eq (1): internal reflectance R_i -> the reflectance factor measured in geometry g,
/// R_m = (1 − k1)(1 − k2)·R_i / (1 − k2·R_i) + k_ins·k1.
double saunderson_measured_Abed2013(double R_i, const SaundersonGeometry& g);
/// Eq (2): measured reflectance factor R_m -> internal reflectance,
/// R_i = (R_m − k_ins·k1) / ((1 − k1)(1 − k2) + k2·R_m − k_ins·k1·k2).
double saunderson_internal_Abed2013(double R_m, const SaundersonGeometry& g);

/// Eq (3) in closed form (eq 2 with `measurement`, then eq 1 with `capture`):
///   R_m,c = (1 − k1c)(1 − k2c)(R_m − k_ins·k1)
///           / ((1 − k1)(1 − k2) − k_ins·k1·k2 + k_ins·k1·k2c + R_m(k2 − k2c)) + k_ins,c·k1c
/// with (k1, k2, k_ins) the measurement and (k1c, k2c, k_ins,c) the capture coefficients.
double saunderson_convert_Abed2013(double R_m, const SaundersonGeometry& measurement,
                                   const SaundersonGeometry& capture);

/// Eq (4): R' = (R + α) / (β·R + γ).
struct ThreeParameter {
  double alpha = 0, beta = 0, gamma = 1;
  double apply(double R) const { return (R + alpha) / (beta * R + gamma); }  // eq (4)
};
/// Appendix A, eqs (15)-(21), derived again with the role naming above:
///   A = (1 − k1c)(1 − k2c), B = k2 − k2c, C = (1 − k1)(1 − k2) − k_ins·k1·k2 + k_ins·k1·k2c,
///   D = k_ins,c·k1c, E = (1 − k1c)(1 − k2c)·k_ins·k1,
///   eq (3) = (A·R − E)/(B·R + C) + D = ((A + DB)·R + DC − E)/(B·R + C), so
///   α = (DC − E)/(A + DB), β = B/(A + DB), γ = C/(A + DB).
/// Error(IllPosed) when A + DB = 0 (k1c = 1 or k2c = 1 with no specular term: every patch
/// would read the same).
ThreeParameter three_parameter_Abed2013(const SaundersonGeometry& measurement, const SaundersonGeometry& capture);

/// Eq (5): R' = μ·R + ρ.
struct ScalerOffset {
  double mu = 1, rho = 0;
  double apply(double R) const { return mu * R + rho; }  // eq (5)
};
/// Appendix B, eqs (22)-(25): with k2 = k2c eq (3) is linear in R_m,
///   μ = (1 − k1c)/(1 − k1),  ρ = k_ins,c·k1c − μ·k_ins·k1.
/// (Printed with the primes on the measurement, see the errata above.) The capture's k2 is
/// ignored: the appendix sets it equal to the measurement's.
ScalerOffset scaler_offset_Abed2013(const SaundersonGeometry& measurement, const SaundersonGeometry& capture);

/// A literature geometry for one instrument or capture set-up: the Saunderson coefficients the
/// paper recommends as starting values, with where each number comes from.
struct SaundersonPreset {
  std::string id;       ///< "d8-sci", "d8-sce", "45-0", "diffuse-booth", "45-0-dual", ...
  std::string label;    ///< human-readable
  std::string role;     ///< "measurement", "capture" or "both"
  SaundersonGeometry geometry;
  std::string source;   ///< the paper and passage (or table) each coefficient comes from
};
/// Every preset, in a stable order.
const std::vector<SaundersonPreset>& saunderson_presets();
/// A preset by id; Error(UnknownId) naming the ids otherwise.
const SaundersonPreset& saunderson_preset(const std::string& id);

}  // namespace tristim

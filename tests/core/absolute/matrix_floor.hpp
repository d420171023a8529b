// The colour module's floor on the virtual camera: what eq (4) gives for a stimulus when every
// step before M is exact (no noise, the true OECF inverted, exact n, S, f(r)). The luminance
// module is trained on the projector's equal-tristimulus light E (eq 9), so an exact one returns
//     L(c) = Y · q_c(φ) / q_c(E),   q_c(φ) = Σ C_c(λ) φ(λ) / Σ ȳ(λ) φ(λ)
// (the camera's response per cd/m²). Then
//   * truth − floor is the colour module's error: M fitted on some spectra (the paper's: 24
//     projected colours, i.e. mixtures of three primaries) and applied to others, with a camera
//     that does not meet the Luther condition (eq 3) — metamerism, which no step of the chain
//     before M can remove;
//   * estimate − floor is the chain's own error (noise, OECF fit, normalisation, fusion).
#pragma once
#include <string>

#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/virtual_bracket.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim::test {

/// q_R, q_G, q_B of column k of `spectra` (up to one common constant).
inline Vec3 response_per_luminance(const SpectralData& ssf, const SpectralData& spectra, size_t k) {
  const auto& grid = ssf.wavelengths;
  const SpectralData& cm = cmfs(Observer::CIE1931_2);
  const auto ybar = interpolate_spectrum(cm.wavelengths, cm.values[1], grid);
  const auto phi = interpolate_spectrum(spectra.wavelengths, spectra.values[k], grid, spectra.linear);
  Vec3 C = Vec3::Zero();
  double Y = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    Y += ybar[i] * phi[i];
    for (int c = 0; c < 3; ++c) C[c] += ssf.values[c][i] * phi[i];
  }
  return C / Y;
}

/// Eq (4) with an exact luminance module for column k of `spectra` at luminance Y (cd/m²).
inline Vec3 matrix_floor_XYZ(const AbsoluteProfile& p, const SpectralData& ssf, const SpectralData& spectra, size_t k,
                             double Y) {
  const Vec3 qE = response_per_luminance(ssf, projector_spectra({Vec3(1, 1, 1)}, {"E"}), 0);
  const Vec3 q = response_per_luminance(ssf, spectra, k);
  return p.XYZ(Vec3(Y * q[0] / qE[0], Y * q[1] / qE[1], Y * q[2] / qE[2]));
}

}  // namespace tristim::test

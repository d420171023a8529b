// Colorimetry on tristimulus values: XYZ <-> xyY <-> Lab <-> LCh, colour differences, chromatic
// adaptation and display encoding. Pure functions on Eigen 3-vectors.
//
// Scale convention: XYZ and the white share one scale. For reflective data the perfect diffuser
// has Y = 100 (CIE 15); absolute data (cd/m²) are fine as long as the white is in cd/m² too.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace tristim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// CIE 1931 2° white points of common illuminants, XYZ with Y = 100 (CIE 15:2004 Table T.3,
/// as colour-science's CCS_ILLUMINANTS; used when no spectral white is at hand).
namespace whites {
inline Vec3 D50() { return Vec3(96.4212, 100.0, 82.5188); }
inline Vec3 D65() { return Vec3(95.0489, 100.0, 108.8840); }
}  // namespace whites

/// XYZ -> CIE 1976 L*a*b* relative to white_XYZ (CIE 15:2004 eq 8.1-8.3, with the exact
/// (6/29)^3 and (29/3)^3 constants). L* in 0..100 for 0 <= Y <= Y_white.
Vec3 XYZ_to_Lab(const Vec3& XYZ, const Vec3& white_XYZ);
/// Inverse of XYZ_to_Lab.
Vec3 Lab_to_XYZ(const Vec3& Lab, const Vec3& white_XYZ);

/// XYZ -> (x, y, Y). For black (X+Y+Z = 0) returns the chromaticity of `black_xy` (default D65)
/// with Y = 0, as colour-science does.
Vec3 XYZ_to_xyY(const Vec3& XYZ, const Eigen::Vector2d& black_xy = Eigen::Vector2d(0.3127, 0.3290));
Vec3 xyY_to_XYZ(const Vec3& xyY);
Eigen::Vector2d XYZ_to_xy(const Vec3& XYZ);

/// L*a*b* -> L*, C*ab, hab (degrees, 0..360) and back.
Vec3 Lab_to_LCh(const Vec3& Lab);
Vec3 LCh_to_Lab(const Vec3& LCh);

/// CIE 1976 ΔE*ab: Euclidean distance in L*a*b*.
double delta_E_CIE1976(const Vec3& Lab1, const Vec3& Lab2);
/// CIE 1994 ΔE*94 (graphic arts: kL = 1, K1 = 0.045, K2 = 0.015; textiles: kL = 2, 0.048, 0.014).
/// Lab1 is the reference (its chroma weights SC and SH), as in CIE 116-1995.
double delta_E_CIE1994(const Vec3& Lab1, const Vec3& Lab2, bool textiles = false);

/// CIEDE2000 with its weighted lightness, chroma and hue terms:
/// dE = sqrt(dL² + dC² + dH² + RT·dC·dH) where dL = ΔL'/(kL·SL), dC = ΔC'/(kC·SC),
/// dH = ΔH'/(kH·SH). Signs follow Lab2 - Lab1 (estimate minus reference).
struct DeltaE2000 {
  double dE, dL, dC, dH;
  double RT;  ///< rotation term, eq (21): dE² = dL² + dC² + dH² + RT·dC·dH, |RT| ≤ 2
};
/// CIEDE2000 (Sharma, Wu & Dalal 2005, eqs 1-22), reproducing their test pairs to 1e-4.
DeltaE2000 delta_E_CIE2000_components(const Vec3& Lab1, const Vec3& Lab2, double kL = 1, double kC = 1,
                                      double kH = 1);
double delta_E_CIE2000(const Vec3& Lab1, const Vec3& Lab2, double kL = 1, double kC = 1, double kH = 1);
/// The components' dL = ΔL'/(kL·SL) alone (eqs 8, 12, 18): it depends on L1 and L2 only.
double delta_E_CIE2000_dL(double L1, double L2, double kL = 1);

/// ΔE per pair of rows by method id: "CIE2000", "CIE1994" (graphic arts; Lab1 is the reference)
/// or "CIE1976". Error(UnknownId) for another id, Error(InvalidArgument) when the lists differ in
/// length.
std::vector<double> delta_E(const std::string& method, const std::vector<Vec3>& Lab1, const std::vector<Vec3>& Lab2);

/// F(row, white) for every row: a per-colour function relative to one white (XYZ_to_Lab, ...)
/// over a list of colours.
template <Vec3 (*F)(const Vec3&, const Vec3&)>
std::vector<Vec3> each_row(const std::vector<Vec3>& rows, const Vec3& white) {
  std::vector<Vec3> out;
  out.reserve(rows.size());
  for (const auto& v : rows) out.push_back(F(v, white));
  return out;
}

/// Chromatic adaptation transforms (von Kries-type, full adaptation).
enum class ChromaticAdaptation { Bradford, CAT02, VonKries };
/// 3x3 matrix M with XYZ_dst = M · XYZ_src, adapting from white src_white to dst_white.
Mat3 chromatic_adaptation_matrix(const Vec3& src_white, const Vec3& dst_white,
                                 ChromaticAdaptation method = ChromaticAdaptation::Bradford);

/// XYZ (Y = 1 for the display white, D65) -> sRGB (IEC 61966-2-1). With encode = true the
/// result is gamma-encoded (0..1, values outside the gamut are clipped); otherwise linear,
/// unclipped.
Vec3 XYZ_to_sRGB(const Vec3& XYZ, bool encode = true);
/// IEC 61966-2-1 encoding of one linear value, clipped to [0, 1] first (the one sRGB encoder:
/// swatches, previews and renderings all use it).
double sRGB_encode(double linear);
/// The same per component of linear sRGB.
Vec3 sRGB_encode(const Vec3& linear_RGB);
/// The sRGB linear primaries' matrix (XYZ from linear sRGB, D65, Y = 1).
Mat3 sRGB_to_XYZ_matrix();

}  // namespace tristim

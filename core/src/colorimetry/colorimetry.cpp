#include "tristim/colorimetry/colorimetry.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "tristim/error.hpp"
#include "../detmath.hpp"

namespace tristim {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kEpsilon = 216.0 / 24389.0;  // (6/29)^3
constexpr double kKappa = 24389.0 / 27.0;     // (29/3)^3
double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double deg) { return deg * kPi / 180.0; }
// Lab and CIEDE2000 use detmath's cbrt, atan2, sin, cos and exp: the same bits natively and in wasm.
double f_Lab(double t) { return t > kEpsilon ? detmath::cbrt(t) : (kKappa * t + 16.0) / 116.0; }
double pow7(double x) {
  const double x2 = x * x, x3 = x2 * x;
  return x3 * x3 * x;
}
constexpr double k25pow7 = 6103515625.0;  // 25^7
double norm2(double a, double b) { return std::sqrt(a * a + b * b); }  // no overflow risk at Lab scale
double f_Lab_inv(double f) { return f * f * f > kEpsilon ? f * f * f : (116.0 * f - 16.0) / kKappa; }
}  // namespace

Vec3 XYZ_to_Lab(const Vec3& XYZ, const Vec3& white_XYZ) {
  const double fx = f_Lab(XYZ[0] / white_XYZ[0]);
  const double fy = f_Lab(XYZ[1] / white_XYZ[1]);
  const double fz = f_Lab(XYZ[2] / white_XYZ[2]);
  return Vec3(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
}

Vec3 Lab_to_XYZ(const Vec3& Lab, const Vec3& white_XYZ) {
  const double fy = (Lab[0] + 16.0) / 116.0;
  const double fx = fy + Lab[1] / 500.0;
  const double fz = fy - Lab[2] / 200.0;
  const double yr = Lab[0] > kKappa * kEpsilon ? fy * fy * fy : Lab[0] / kKappa;
  return Vec3(f_Lab_inv(fx) * white_XYZ[0], yr * white_XYZ[1], f_Lab_inv(fz) * white_XYZ[2]);
}

Vec3 XYZ_to_xyY(const Vec3& XYZ, const Eigen::Vector2d& black_xy) {
  const double s = XYZ.sum();
  if (s == 0.0) return Vec3(black_xy[0], black_xy[1], 0.0);
  return Vec3(XYZ[0] / s, XYZ[1] / s, XYZ[1]);
}

Vec3 xyY_to_XYZ(const Vec3& xyY) {
  if (xyY[1] == 0.0) return Vec3(0.0, 0.0, 0.0);
  return Vec3(xyY[0] * xyY[2] / xyY[1], xyY[2], (1.0 - xyY[0] - xyY[1]) * xyY[2] / xyY[1]);
}

Eigen::Vector2d XYZ_to_xy(const Vec3& XYZ) {
  const Vec3 xyY = XYZ_to_xyY(XYZ);
  return Eigen::Vector2d(xyY[0], xyY[1]);
}

Vec3 Lab_to_LCh(const Vec3& Lab) {
  double h = deg(detmath::atan2(Lab[2], Lab[1]));
  if (h < 0) h += 360.0;
  return Vec3(Lab[0], norm2(Lab[1], Lab[2]), h);
}

Vec3 LCh_to_Lab(const Vec3& LCh) {
  return Vec3(LCh[0], LCh[1] * detmath::cos(rad(LCh[2])), LCh[1] * detmath::sin(rad(LCh[2])));
}

double delta_E_CIE1976(const Vec3& Lab1, const Vec3& Lab2) { return (Lab2 - Lab1).norm(); }

double delta_E_CIE1994(const Vec3& Lab1, const Vec3& Lab2, bool textiles) {
  const double kL = textiles ? 2.0 : 1.0, K1 = textiles ? 0.048 : 0.045, K2 = textiles ? 0.014 : 0.015;
  const double C1 = norm2(Lab1[1], Lab1[2]), C2 = norm2(Lab2[1], Lab2[2]);
  const double dL = Lab1[0] - Lab2[0], dC = C1 - C2;
  const double da = Lab1[1] - Lab2[1], db = Lab1[2] - Lab2[2];
  const double dH2 = std::max(0.0, da * da + db * db - dC * dC);
  const double SL = 1.0, SC = 1.0 + K1 * C1, SH = 1.0 + K2 * C1;
  const double tL = dL / (kL * SL), tC = dC / SC;
  return std::sqrt(tL * tL + tC * tC + dH2 / (SH * SH));
}

std::vector<double> delta_E(const std::string& method, const std::vector<Vec3>& Lab1, const std::vector<Vec3>& Lab2) {
  if (Lab1.size() != Lab2.size()) throw Error(ErrorCode::InvalidArgument, "Lab1 and Lab2 differ in length");
  if (method != "CIE2000" && method != "CIE1994" && method != "CIE1976")
    throw Error(ErrorCode::UnknownId, "unknown ΔE method '" + method + "' (CIE2000, CIE1994, CIE1976)");
  std::vector<double> out(Lab1.size());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = method == "CIE2000" ? delta_E_CIE2000(Lab1[i], Lab2[i])
             : method == "CIE1994" ? delta_E_CIE1994(Lab1[i], Lab2[i]) : delta_E_CIE1976(Lab1[i], Lab2[i]);
  return out;
}

double delta_E_CIE2000_dL(double L1, double L2, double kL) {
  const double dLp = L2 - L1;                                              // eq (8)
  const double Lbarp = 0.5 * (L1 + L2);                                    // eq (12)
  const double Lm50 = (Lbarp - 50.0) * (Lbarp - 50.0);
  const double SL = 1.0 + 0.015 * Lm50 / std::sqrt(20.0 + Lm50);          // eq (18)
  return dLp / (kL * SL);
}

DeltaE2000 delta_E_CIE2000_components(const Vec3& Lab1, const Vec3& Lab2, double kL, double kC, double kH) {
  // Sharma, Wu & Dalal (2005), "The CIEDE2000 color-difference formula", eqs (1)-(22).
  const double L1 = Lab1[0], a1 = Lab1[1], b1 = Lab1[2];
  const double L2 = Lab2[0], a2 = Lab2[1], b2 = Lab2[2];
  const double C1 = norm2(a1, b1), C2 = norm2(a2, b2);                     // eq (2)
  const double Cbar = 0.5 * (C1 + C2);                                     // eq (3)
  const double Cbar7 = pow7(Cbar);
  const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + k25pow7)));    // eq (4)
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;                 // eq (5)
  const double C1p = norm2(a1p, b1), C2p = norm2(a2p, b2);                 // eq (6)
  auto hue = [](double b, double ap) {                                     // eq (7)
    if (b == 0.0 && ap == 0.0) return 0.0;
    double h = deg(detmath::atan2(b, ap));
    return h < 0 ? h + 360.0 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
  const double dCp = C2p - C1p;                                            // eq (9)
  double dhp = 0.0;                                                        // eq (10)
  if (C1p * C2p != 0.0) {
    dhp = h2p - h1p;
    if (dhp > 180.0) dhp -= 360.0;
    else if (dhp < -180.0) dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * detmath::sin(rad(dhp / 2.0));  // eq (11)
  const double Cbarp = 0.5 * (C1p + C2p);                                  // eq (13)
  double hbarp = h1p + h2p;                                                // eq (14)
  if (C1p * C2p != 0.0) {
    if (std::abs(h1p - h2p) <= 180.0) hbarp = 0.5 * (h1p + h2p);
    else if (h1p + h2p < 360.0) hbarp = 0.5 * (h1p + h2p + 360.0);
    else hbarp = 0.5 * (h1p + h2p - 360.0);
  }
  // eq (15), T = 1 − 0.17 cos(h̄' − 30°) + 0.24 cos(2h̄') + 0.32 cos(3h̄' + 6°) − 0.20 cos(4h̄' − 63°), its
  // multiple angles from cos h̄' and sin h̄' (one cosine and one sine instead of four cosines).
  const double ch = detmath::cos(rad(hbarp)), sh = detmath::sin(rad(hbarp));
  const double c2 = 2.0 * ch * ch - 1.0, s2 = 2.0 * sh * ch;
  const double c3 = ch * (4.0 * ch * ch - 3.0), s3 = sh * (3.0 - 4.0 * sh * sh);
  const double c4 = 2.0 * c2 * c2 - 1.0, s4 = 2.0 * s2 * c2;
  static const double cos30 = detmath::cos(rad(30.0)), sin30 = detmath::sin(rad(30.0)), cos6 = detmath::cos(rad(6.0)),
                      sin6 = detmath::sin(rad(6.0)), cos63 = detmath::cos(rad(63.0)), sin63 = detmath::sin(rad(63.0));
  const double T = 1.0 - 0.17 * (ch * cos30 + sh * sin30) + 0.24 * c2 + 0.32 * (c3 * cos6 - s3 * sin6) -
                   0.20 * (c4 * cos63 + s4 * sin63);
  const double t = (hbarp - 275.0) / 25.0;
  const double dtheta = 30.0 * detmath::exp(-t * t);                           // eq (16)
  const double Cbarp7 = pow7(Cbarp);
  const double RC = 2.0 * std::sqrt(Cbarp7 / (Cbarp7 + k25pow7));          // eq (17)
  const double SC = 1.0 + 0.045 * Cbarp;                                   // eq (19)
  const double SH = 1.0 + 0.015 * Cbarp * T;                               // eq (20)
  const double RT = -detmath::sin(rad(2.0 * dtheta)) * RC;                     // eq (21)
  DeltaE2000 r;
  r.dL = delta_E_CIE2000_dL(L1, L2, kL);
  r.dC = dCp / (kC * SC);
  r.dH = dHp / (kH * SH);
  r.RT = RT;
  r.dE = std::sqrt(std::max(0.0, r.dL * r.dL + r.dC * r.dC + r.dH * r.dH + RT * r.dC * r.dH));  // eq (22)
  return r;
}

double delta_E_CIE2000(const Vec3& Lab1, const Vec3& Lab2, double kL, double kC, double kH) {
  return delta_E_CIE2000_components(Lab1, Lab2, kL, kC, kH).dE;
}

Mat3 chromatic_adaptation_matrix(const Vec3& src_white, const Vec3& dst_white, ChromaticAdaptation method) {
  Mat3 M = Mat3::Identity();
  switch (method) {
    case ChromaticAdaptation::Bradford:
      M << 0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296;
      break;
    case ChromaticAdaptation::CAT02:
      M << 0.7328, 0.4296, -0.1624, -0.7036, 1.6975, 0.0061, 0.0030, 0.0136, 0.9834;
      break;
    case ChromaticAdaptation::VonKries:  // Hunt-Pointer-Estévez, normalised to D65
      M << 0.40024, 0.70760, -0.08081, -0.22630, 1.16532, 0.04570, 0.0, 0.0, 0.91822;
      break;
  }
  const Vec3 src = M * src_white, dst = M * dst_white;
  return M.inverse() * dst.cwiseQuotient(src).asDiagonal() * M;
}

Mat3 sRGB_to_XYZ_matrix() {
  // Derived from the IEC 61966-2-1 primaries and the D65 white chromaticity (0.3127, 0.3290),
  // as colour-science's RGB_COLOURSPACE_sRGB does (normalised primary matrix, SMPTE RP 177).
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  Mat3 P;
  for (int i = 0; i < 3; ++i) P.col(i) = Vec3(xy[i][0] / xy[i][1], 1.0, (1.0 - xy[i][0] - xy[i][1]) / xy[i][1]);
  const Vec3 W = xyY_to_XYZ(Vec3(0.3127, 0.3290, 1.0));
  const Vec3 S = P.inverse() * W;
  return P * S.asDiagonal();
}

double sRGB_encode(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * detmath::pow(c, 1.0 / 2.4) - 0.055;
}

Vec3 sRGB_encode(const Vec3& linear_RGB) {
  return Vec3(sRGB_encode(linear_RGB[0]), sRGB_encode(linear_RGB[1]), sRGB_encode(linear_RGB[2]));
}

Vec3 XYZ_to_sRGB(const Vec3& XYZ, bool encode) {
  static const Mat3 inv = sRGB_to_XYZ_matrix().inverse();
  const Vec3 rgb = inv * XYZ;
  return encode ? sRGB_encode(rgb) : rgb;
}

}  // namespace tristim

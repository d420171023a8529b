// DNG Camera Profiles (profile/dcp.hpp): the calibration illuminants, a profile's ColorMatrix and
// ForwardMatrix (DNG 1.6 chapter 6 "Camera to XYZ (D50) Transform"), and the reference pipeline's
// camera -> XYZ D50 for a camera neutral that tests and `tristim inspect` check a DCP with.
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "export_dcp_internal.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/version.hpp"

namespace tristim {

using namespace dcp_internal;

// ---------------------------------------------------------------------------- illuminants

const std::vector<DcpIlluminant>& dcp_illuminants() {
  // Temperatures: the DNG SDK's for each code (dng_camera_profile IlluminantToTemperature), which
  // is what readers interpolate with; chromaticities: the CIE's (CIE 15:2004 table T.3; F2 and
  // F11 table T.8), which the matrices are built for when a profile's own white is not given.
  static const std::vector<DcpIlluminant> rows = {
      {17, "A", "Standard Light A", 2850, 0.44757, 0.40745},
      {14, "F2", "Cool White Fluorescent", 4150, 0.37208, 0.37529},
      {14, "F11", "Cool White Fluorescent", 4150, 0.38052, 0.37713},
      {23, "D50", "D50", 5000, 0.34567, 0.35850},
      {20, "D55", "D55", 5500, 0.33242, 0.34743},
      {21, "D65", "D65", 6500, 0.31271, 0.32902},
      {22, "D75", "D75", 7500, 0.29902, 0.31485},
  };
  return rows;
}

const DcpIlluminant& dcp_illuminant(const std::string& id) {
  for (const auto& r : dcp_illuminants())
    if (r.id == id) return r;
  std::string known;
  for (const auto& r : dcp_illuminants()) known += (known.empty() ? "" : ", ") + r.id;
  throw Error(ErrorCode::UnknownId, "illuminant '" + id + "' has no DNG CalibrationIlluminant code (a DCP can carry " +
                                        known + ")");
}

std::string dcp_illuminant_name(int code) {
  switch (code) {
    case 0: return "Unknown";
    case 1: return "Daylight";
    case 2: return "Fluorescent";
    case 3: return "Tungsten (Incandescent)";
    case 4: return "Flash";
    case 9: return "Fine Weather";
    case 10: return "Cloudy";
    case 11: return "Shade";
    case 12: return "Daylight Fluorescent";
    case 13: return "Day White Fluorescent";
    case 14: return "Cool White Fluorescent";
    case 15: return "White Fluorescent";
    case 16: return "Warm White Fluorescent";
    case 17: return "Standard Light A";
    case 18: return "Standard Light B";
    case 19: return "Standard Light C";
    case 20: return "D55";
    case 21: return "D65";
    case 22: return "D75";
    case 23: return "D50";
    case 24: return "ISO Studio Tungsten";
    case 255: return "Other";
    default: return "";
  }
}

double dcp_illuminant_temperature(int code) {
  switch (code) {  // the DNG SDK's table (dng_camera_profile.cpp IlluminantToTemperature)
    case 17: case 3: return 2850;
    case 24: return 3200;
    case 23: return 5000;
    case 20: case 1: case 9: case 4: case 18: return 5500;
    case 21: case 19: case 10: return 6500;
    case 22: case 11: return 7500;
    case 12: return (5700.0 + 7100.0) * 0.5;
    case 13: return (4600.0 + 5500.0) * 0.5;
    case 14: case 2: return (3800.0 + 4500.0) * 0.5;
    case 15: return (3250.0 + 3800.0) * 0.5;
    case 16: return (2600.0 + 3250.0) * 0.5;
    default: return 0;
  }
}

// ---------------------------------------------------------------------------- colour helpers

Vec3 dcp_d50() { return Vec3(0.3457 / 0.3585, 1.0, (1.0 - 0.3457 - 0.3585) / 0.3585); }

Mat3 prophoto_to_xyz() {
  Mat3 m;  // the DNG SDK's dng_space_ProPhoto (ROMM RGB, D50)
  m << 0.7977, 0.1352, 0.0313,
       0.2880, 0.7119, 0.0001,
       0.0000, 0.0000, 0.8249;
  return m;
}


namespace {

Observer profile_observer(const Profile& p) {
  return p.observer.find("1964") != std::string::npos ? Observer::CIE1964_10 : Observer::CIE1931_2;
}

/// ∂model/∂RGB at rgb by central differences (exact for the 3×3 model up to rounding).
Mat3 jacobian(const Model& model, const Vec3& rgb) {
  Mat3 J;
  const double scale = rgb.cwiseAbs().maxCoeff();
  for (int c = 0; c < 3; ++c) {
    const double h = 1e-6 * std::max(std::abs(rgb[c]), 1e-3 * scale);
    Vec3 a = rgb, b = rgb;
    a[c] += h;
    b[c] -= h;
    J.col(c) = (predict(model, a) - predict(model, b)) / (2 * h);
  }
  return J;
}

/// The camera RGB the model maps to `white` (Newton's method, damped), or Error(ProfileInvalid).
Vec3 camera_white(const Model& model, const Vec3& white) {
  // Start on the neutral axis at the right luminance: exact for an exposure-invariant model whose
  // neutral is (1,1,1), close for the others.
  const Vec3 one = Vec3::Ones();
  const double y1 = predict(model, one)[1];
  Vec3 w = one * (y1 > 0 ? white[1] / y1 : 1.0);
  double r = (predict(model, w) - white).norm();
  for (int it = 0; it < 100 && r > 1e-13 * white.norm(); ++it) {
    const Mat3 J = jacobian(model, w);
    Eigen::FullPivLU<Mat3> lu(J);
    if (!lu.isInvertible()) break;
    const Vec3 step = lu.solve(white - predict(model, w));
    double t = 1;
    bool improved = false;
    for (int k = 0; k < 40; ++k, t *= 0.5) {
      const Vec3 next = w + t * step;
      const double rn = (predict(model, next) - white).norm();
      if (std::isfinite(rn) && rn < r) {
        w = next;
        r = rn;
        improved = true;
        break;
      }
    }
    if (!improved) break;
  }
  if (!(r <= 1e-9 * white.norm()) || !(w.minCoeff() > 0))
    throw Error(ErrorCode::ProfileInvalid, "the profile's model maps no positive camera RGB to its white (residual " +
                                               std::to_string(r) + "): no camera neutral for a DCP");
  return w;
}

}  // namespace

std::string profile_illuminant_id(const Profile& p) {
  if (p.has_recipe && p.recipe.reference.chart != "file") return p.recipe.reference.illuminant;
  return p.illuminant;
}

DcpCalibration dcp_calibration(const Profile& p, const std::string& illuminant_id) {
  if (p.has_linearisation)
    throw Error(ErrorCode::InvalidArgument, "the profile takes stored (non-linear) values (linearisation " +
                                                p.linearisation.choice.method +
                                                "): a DCP applies to linear RAW data; fit the profile on a RAW file");
  const std::string id = illuminant_id.empty() ? profile_illuminant_id(p) : illuminant_id;
  if (id == "custom" || id.empty())
    throw Error(ErrorCode::UnknownId, "the profile does not say under which illuminant its reference was computed "
                                      "(white " + std::to_string(p.white[0]) + ", " + std::to_string(p.white[1]) + ", " +
                                      std::to_string(p.white[2]) + "): name it (--illuminant D50, A, …)");
  DcpCalibration c;
  c.illuminant = dcp_illuminant(id);
  // The white of the model's XYZ: the profile's own white when it has the illuminant's
  // chromaticity (the fit's units exactly), else the illuminant's white (tristim's SPD and the
  // profile's observer) at the profile white's luminance.
  Vec3 white = p.white;
  {
    const Vec3 wi = illuminant_white_XYZ(illuminant_spd(id), profile_observer(p));
    const Eigen::Vector2d a = XYZ_to_xy(white), b = XYZ_to_xy(wi);
    if ((a - b).cwiseAbs().maxCoeff() > 1e-3) white = wi * (p.white[1] / wi[1]);
  }
  const ModelInfo& info = model_info(p.model.id);
  check_coefficient_shape(p.model, info);
  c.camera_white = info.linear ? Vec3(p.model.coefficients.leftCols(3).fullPivLu().solve(white))
                               : camera_white(p.model, white);
  if (!(c.camera_white.minCoeff() > 0) || !c.camera_white.allFinite())
    throw Error(ErrorCode::ProfileInvalid, "the profile's camera white is not positive: no camera neutral for a DCP");
  const Vec3& w = c.camera_white;
  c.neutral = w / w.maxCoeff();
  Mat3 J = info.linear ? Mat3(p.model.coefficients.leftCols(3)) : jacobian(p.model, w);
  // Rank-one correction so that J·w is the white exactly: nothing for an exposure-invariant model
  // (Euler: J·w = model(w)), the white's own rendering for a model with an offset or powers.
  J += (white - J * w) * w.transpose() / w.squaredNorm();
  c.linear = J;
  Eigen::FullPivLU<Mat3> lu(J);
  if (!lu.isInvertible() || !J.allFinite())
    throw Error(ErrorCode::IllConditioned, "the profile's camera -> XYZ matrix is singular: no DCP");
  // ColorMatrix (DNG 1.6 §6 "Translating White Balance xy Coordinates to Camera Neutral"): XYZ
  // under the illuminant -> camera, scaled so that the illuminant's white (Y = 1) maps to the
  // camera neutral, whose largest component is 1.
  c.color_matrix = lu.inverse() * (white[1] / w.maxCoeff());
  // ForwardMatrix (§6 "Camera to XYZ (D50) Transform"): white-balanced camera -> XYZ D50, rows
  // scaled so that (1,1,1) maps to D50 exactly, as the DNG SDK normalises it on reading.
  const Mat3 adapt = chromatic_adaptation_matrix(white / white[1], dcp_d50(), ChromaticAdaptation::Bradford);
  Mat3 fm = adapt * J * w.asDiagonal();
  const Vec3 sums = fm * Vec3::Ones(), d50 = dcp_d50();
  for (int r = 0; r < 3; ++r) fm.row(r) *= d50[r] / sums[r];
  c.forward_matrix = fm;
  return c;
}

// ---------------------------------------------------------------------------- reference pipeline

namespace {

/// Correlated colour temperature of xy by Robertson's method as the DNG SDK computes it
/// (dng_temperature::Set_xy_coord; isotherm table of Wyszecki & Stiles, table 1(3.11)).
double xy_to_temperature(double x, double y) {
  static const double table[31][4] = {  // mired, u, v, slope
      {0, 0.18006, 0.26352, -0.24341},   {10, 0.18066, 0.26589, -0.25479},  {20, 0.18133, 0.26846, -0.26876},
      {30, 0.18208, 0.27119, -0.28539},  {40, 0.18293, 0.27407, -0.30470},  {50, 0.18388, 0.27709, -0.32675},
      {60, 0.18494, 0.28021, -0.35156},  {70, 0.18611, 0.28342, -0.37915},  {80, 0.18740, 0.28668, -0.40955},
      {90, 0.18880, 0.28997, -0.44278},  {100, 0.19032, 0.29326, -0.47888}, {125, 0.19462, 0.30141, -0.58204},
      {150, 0.19962, 0.30921, -0.70471}, {175, 0.20525, 0.31647, -0.84901}, {200, 0.21142, 0.32312, -1.0182},
      {225, 0.21807, 0.32909, -1.2168},  {250, 0.22511, 0.33439, -1.4512},  {275, 0.23247, 0.33904, -1.7298},
      {300, 0.24010, 0.34308, -2.0637},  {325, 0.24792, 0.34655, -2.4681},  {350, 0.25591, 0.34951, -2.9641},
      {375, 0.26400, 0.35200, -3.5814},  {400, 0.27218, 0.35407, -4.3633},  {425, 0.28039, 0.35577, -5.3762},
      {450, 0.28863, 0.35714, -6.7262},  {475, 0.29685, 0.35823, -8.5955},  {500, 0.30505, 0.35907, -11.324},
      {525, 0.31320, 0.35968, -15.628},  {550, 0.32129, 0.36011, -23.325},  {575, 0.32931, 0.36038, -40.770},
      {600, 0.33724, 0.36051, -116.45}};
  const double den = 1.5 - x + 6 * y;
  const double u = 2 * x / den, v = 3 * y / den;
  double last_dt = 0;
  for (int i = 1; i <= 30; ++i) {
    double du = 1, dv = table[i][3];
    const double len = std::sqrt(1 + dv * dv);
    du /= len;
    dv /= len;
    double dt = -(u - table[i][1]) * dv + (v - table[i][2]) * du;
    if (dt <= 0 || i == 30) {
      if (dt > 0) dt = 0;
      dt = -dt;
      const double f = i == 1 ? 0 : dt / (last_dt + dt);
      return 1e6 / (table[i - 1][0] * f + table[i][0] * (1 - f));
    }
    last_dt = dt;
  }
  return 0;  // not reached
}

}  // namespace

DcpTransform dcp_camera_to_xyz(const Dcp& d, const Vec3& neutral_in, int illuminant) {
  if (!(neutral_in.minCoeff() > 0)) throw Error(ErrorCode::InvalidArgument, "a camera neutral must be positive");
  double t1 = dcp_illuminant_temperature(d.illuminant1), t2 = dcp_illuminant_temperature(d.illuminant2);
  const bool dual = d.has_color_matrix2 && t1 > 0 && t2 > 0 && t1 != t2;
  // The DNG SDK orders the two calibrations by temperature (dng_color_spec).
  const bool swapped = dual && t1 > t2;
  if (swapped) std::swap(t1, t2);
  auto weight = [&](const Eigen::Vector2d& xy) {
    if (!dual || illuminant == 1) return 1.0;
    if (illuminant == 2) return 0.0;
    const double t = xy_to_temperature(xy[0], xy[1]);
    double g = t <= t1 ? 1.0 : t >= t2 ? 0.0 : (1 / t - 1 / t2) / (1 / t1 - 1 / t2);
    return swapped ? 1 - g : g;  // g weighs the lower temperature; report it for illuminant 1
  };
  auto mix = [&](const Mat3& a, const Mat3& b, double g) { return Mat3(g * a + (1 - g) * b); };
  const Vec3 d50 = dcp_d50();
  // §6: neutral -> xy by iterating "xy -> interpolated ColorMatrix -> xy" from D50 (the SDK's
  // NeutralToXY: 30 passes, the mean of the last two when it oscillates).
  Eigen::Vector2d last(0.3457, 0.3585);
  double g = 1;
  for (int pass = 0; pass < 30; ++pass) {
    g = weight(last);
    const Mat3 cm = d.has_color_matrix2 ? mix(d.color_matrix1, d.color_matrix2, g) : d.color_matrix1;
    const Vec3 xyz = cm.inverse() * neutral_in;
    Eigen::Vector2d next = XYZ_to_xy(xyz);
    if (std::abs(next[0] - last[0]) + std::abs(next[1] - last[1]) < 1e-7) {
      last = next;
      break;
    }
    if (pass == 29) next = (last + next) * 0.5;
    last = next;
  }
  DcpTransform t;
  t.white_xy = last;
  t.weight1 = g = weight(last);
  const Mat3 cm = d.has_color_matrix2 ? mix(d.color_matrix1, d.color_matrix2, g) : d.color_matrix1;
  // The camera white of that xy, largest component 1 (the SDK pins it to [0.001, 1]).
  Vec3 cam_white = cm * xy_to_XYZ(last[0], last[1]);
  cam_white = (cam_white / cam_white.maxCoeff()).cwiseMax(0.001).cwiseMin(1.0);
  if (d.has_forward_matrix1) {
    Mat3 fm = d.has_forward_matrix2 ? mix(d.forward_matrix1, d.forward_matrix2, g) : d.forward_matrix1;
    const Vec3 sums = fm * Vec3::Ones();
    for (int r = 0; r < 3; ++r) fm.row(r) *= d50[r] / sums[r];  // the SDK's NormalizeForwardMatrix
    t.camera_to_xyz = fm * cam_white.cwiseInverse().asDiagonal();
  } else {
    Mat3 pcs_to_camera = cm * chromatic_adaptation_matrix(d50, xy_to_XYZ(last[0], last[1]), ChromaticAdaptation::Bradford);
    pcs_to_camera /= (pcs_to_camera * d50).maxCoeff();
    t.camera_to_xyz = pcs_to_camera.inverse();
  }
  return t;
}

}  // namespace tristim

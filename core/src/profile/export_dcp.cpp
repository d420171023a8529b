// DNG Camera Profiles (profile/dcp.hpp): derivation from a tristim profile, the TIFF-structure
// writer and reader of chapter 7 of the DNG Specification 1.6.0.0, and the reference pipeline of
// its chapter 6 that the tests and `tristim inspect` check a DCP with. No TIFF library writes the
// "IIRC" magic or reads a file that has it (libtiff refuses it), hence a small writer and reader
// of our own.
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/version.hpp"

namespace tristim {

namespace {

// Limits of the HueSatMap/LookTable dims, written and read (DcpOptions::hue_sat_map).
constexpr std::uint32_t kMaxHue = 360, kMaxSat = 256, kMaxVal = 256;
constexpr std::uint64_t kMaxNodes = 2000000;

// TIFF field types (TIFF 6.0 §2).
enum : std::uint16_t { kByte = 1, kAscii = 2, kShort = 3, kLong = 4, kRational = 5, kSRational = 10, kFloat = 11 };

std::size_t type_size(std::uint16_t type) {
  switch (type) {
    case 1: case 2: case 6: case 7: return 1;
    case 3: case 8: return 2;
    case 4: case 9: case 11: case 13: return 4;
    case 5: case 10: case 12: return 8;
    default: return 0;
  }
}

std::string fmt_code(int code) {
  const std::string n = dcp_illuminant_name(code);
  return std::to_string(code) + (n.empty() ? "" : " (" + n + ")");
}

}  // namespace

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

Vec3 xy_to_XYZ(double x, double y) { return Vec3(x / y, 1.0, (1.0 - x - y) / y); }

/// Hexcone HSV with hue in degrees [0, 360), as the DNG SDK's DNG_RGBtoHSV (hue in sixths there).
Vec3 rgb_to_hsv(const Vec3& rgb) {
  const double mx = rgb.maxCoeff(), mn = rgb.minCoeff(), gap = mx - mn;
  double h = 0, s = 0;
  if (gap > 0 && mx > 0) {
    if (rgb[0] == mx) {
      h = (rgb[1] - rgb[2]) / gap;
      if (h < 0) h += 6;
    } else if (rgb[1] == mx) {
      h = 2 + (rgb[2] - rgb[0]) / gap;
    } else {
      h = 4 + (rgb[0] - rgb[1]) / gap;
    }
    s = gap / mx;
  }
  return Vec3(h * 60, s, mx);
}

Vec3 hsv_to_rgb(const Vec3& hsv) {
  const double v = hsv[2], s = hsv[1];
  if (s <= 0) return Vec3(v, v, v);
  double h = std::fmod(hsv[0], 360.0);
  if (h < 0) h += 360;
  h /= 60;
  const int i = std::min(5, static_cast<int>(std::floor(h)));
  const double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0: return Vec3(v, t, p);
    case 1: return Vec3(q, v, p);
    case 2: return Vec3(p, v, t);
    case 3: return Vec3(p, q, v);
    case 4: return Vec3(t, p, v);
    default: return Vec3(v, p, q);
  }
}

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

// ---------------------------------------------------------------------------- HueSatMap

namespace {

/// The HueSatMap of one profile against its forward matrix: per node of the ProPhoto HSV grid,
/// what turns the ForwardMatrix's rendering of a camera RGB into the model's (hue shift in
/// degrees, saturation and value scales). Nodes whose camera RGB would be negative (outside
/// what a camera records) hold the correction of the last valid saturation at their hue.
std::vector<float> hue_sat_data(const Profile& p, const DcpCalibration& c, std::uint32_t H, std::uint32_t S,
                                std::uint32_t V, double rgb_scale) {
  const Mat3 pp = prophoto_to_xyz(), pp_inv = pp.inverse();
  const Mat3 fm_inv = c.forward_matrix.inverse();
  const Vec3 white = c.linear * c.camera_white;
  const Mat3 adapt = chromatic_adaptation_matrix(white / white[1], dcp_d50(), ChromaticAdaptation::Bradford);
  const double scale = rgb_scale > 0 ? rgb_scale : p.rgb_max;
  if (!(scale > 0) || !std::isfinite(scale))
    throw Error(ErrorCode::InvalidArgument, "DCP HueSatMap: the camera value of DNG 1.0 must be positive");
  const double wmax = c.camera_white.maxCoeff();
  const double k = wmax / (scale * white[1]);  // DNG XYZ (1 = white level) per model XYZ
  const bool invariant = model_info(p.model.id).exposure_invariant;
  // The value of a 2.5D table (V = 1) and of every slab of an exposure-invariant model: half the
  // perfect white's value, the middle of a chart's range (any value gives the same table then).
  const double v_ref = 0.5 * wmax / scale;
  std::vector<float> data(static_cast<std::size_t>(H) * S * V * 3);
  auto node = [&](std::uint32_t vi, std::uint32_t hi, std::uint32_t si) -> float* {
    return data.data() + 3 * ((static_cast<std::size_t>(vi) * H + hi) * S + si);
  };
  auto slab = [&](std::uint32_t vi, double v) {
    for (std::uint32_t hi = 0; hi < H; ++hi) {
      float last[3] = {0, 1, 1};
      for (std::uint32_t si = 0; si < S; ++si) {
        const double h = 360.0 * hi / H, s = S > 1 ? static_cast<double>(si) / (S - 1) : 0.0;
        const Vec3 xyz = pp * hsv_to_rgb(Vec3(h, s, v));
        const Vec3 cam = c.neutral.cwiseProduct(fm_inv * xyz);  // DNG camera RGB rendered at the node
        bool ok = cam.minCoeff() > 0 && cam.allFinite();
        Vec3 hsv;
        if (ok) {
          const Vec3 target = pp_inv * (k * (adapt * predict(p.model, Vec3(cam * scale))));
          hsv = rgb_to_hsv(target);
          ok = target.allFinite() && hsv[2] > 0 && (si == 0 || hsv[1] > 0);
        }
        float* e = node(vi, hi, si);
        if (!ok) {
          std::copy(last, last + 3, e);
          continue;
        }
        double dh = 0, ss = 1;
        if (si > 0) {
          dh = std::remainder(hsv[0] - h, 360.0);
          ss = hsv[1] / s;
        }
        e[0] = static_cast<float>(dh);
        e[1] = static_cast<float>(ss);
        e[2] = static_cast<float>(hsv[2] / v);
        std::copy(e, e + 3, last);
      }
    }
  };
  if (V == 1 || invariant) {
    slab(0, v_ref);
    for (std::uint32_t vi = 1; vi < V; ++vi) std::copy(node(0, 0, 0), node(1, 0, 0), node(vi, 0, 0));
  } else {
    for (std::uint32_t vi = 1; vi < V; ++vi) slab(vi, static_cast<double>(vi) / (V - 1));
    // Value 0 is black, where the change is undefined: the first slab's change holds below it.
    std::copy(node(1, 0, 0), node(2, 0, 0), node(0, 0, 0));
  }
  return data;
}

void check_dims(std::uint32_t h, std::uint32_t s, std::uint32_t v, const std::string& what, bool reading) {
  if (h < 1 || s < 2 || v < 1)
    throw Error(reading ? ErrorCode::ProfileInvalid : ErrorCode::InvalidArgument,
                what + " divisions " + std::to_string(h) + "," + std::to_string(s) + "," + std::to_string(v) +
                    ": hue >= 1, saturation >= 2 and value >= 1 (DNG 1.6 ProfileHueSatMapDims)");
  if (h > kMaxHue || s > kMaxSat || v > kMaxVal || static_cast<std::uint64_t>(h) * s * v > kMaxNodes)
    throw Error(reading ? ErrorCode::LimitExceeded : ErrorCode::InvalidArgument,
                what + " divisions " + std::to_string(h) + "," + std::to_string(s) + "," + std::to_string(v) +
                    " beyond the limits (hue <= 360, saturation <= 256, value <= 256, at most 2,000,000 nodes)");
}

std::string default_name(const Profile& p, const std::string& illuminant) {
  return "tristim " + p.model.id + " " + objective_id(p.objective) + " " + illuminant;
}

}  // namespace

Dcp make_dcp(const Profile& first, const DcpOptions& o, const Profile* second) {
  if (o.camera_model.empty())
    throw Error(ErrorCode::InvalidArgument, "a DCP needs the camera's UniqueCameraModel (the profile JSON names no camera)");
  if (o.embed_policy > 3) throw Error(ErrorCode::InvalidArgument, "ProfileEmbedPolicy is 0..3");
  const bool map = o.hue_sat_map[0] != 0 || o.hue_sat_map[1] != 0 || o.hue_sat_map[2] != 0;
  if (map) {
    for (int d : o.hue_sat_map)
      if (d < 0) throw Error(ErrorCode::InvalidArgument, "HueSatMap divisions must be positive");
    check_dims(static_cast<std::uint32_t>(o.hue_sat_map[0]), static_cast<std::uint32_t>(o.hue_sat_map[1]),
               static_cast<std::uint32_t>(o.hue_sat_map[2]), "HueSatMap", false);
  }
  if (o.rgb_scale < 0 || !std::isfinite(o.rgb_scale))
    throw Error(ErrorCode::InvalidArgument, "the camera value of DNG 1.0 (--rgb-scale) must be positive");
  const Profile* p1 = &first;
  const Profile* p2 = second;
  DcpCalibration c1 = dcp_calibration(first, o.illuminant), c2;
  if (p2) {
    c2 = dcp_calibration(*second, o.second_illuminant);
    if (c1.illuminant.code == c2.illuminant.code || c1.illuminant.temperature == c2.illuminant.temperature)
      throw Error(ErrorCode::SameIlluminant,
                  "both profiles are calibrated under " + c1.illuminant.id + " and " + c2.illuminant.id +
                      " (CalibrationIlluminant " + fmt_code(c1.illuminant.code) + " and " + fmt_code(c2.illuminant.code) +
                      "): a dual-illuminant DCP needs two illuminants of different colour temperature (DNG readers "
                      "drop the second matrix otherwise)");
    // Illuminant 1 is the lower colour temperature: readers interpolate between them in inverse CCT.
    if (c1.illuminant.temperature > c2.illuminant.temperature) {
      std::swap(c1, c2);
      std::swap(p1, p2);
    }
  }
  Dcp d;
  d.unique_camera_model = o.camera_model;
  d.profile_name = !o.profile_name.empty() ? o.profile_name
                   : p2 ? default_name(*p1, c1.illuminant.id) + " + " + default_name(*p2, c2.illuminant.id).substr(8)
                        : default_name(*p1, c1.illuminant.id);
  d.copyright = o.copyright.empty() ? std::string("Generated by tristim ") + kVersion + "; no copyright asserted" : o.copyright;
  // The profile was fitted on raw values without the DNG's CameraCalibration matrices (LibRaw does
  // not apply them); a signature no camera writes keeps readers from applying them (§6 "Camera
  // Calibration": only when ProfileCalibrationSignature equals CameraCalibrationSignature).
  d.calibration_signature = "tristim";
  d.embed_policy = o.embed_policy;
  d.illuminant1 = c1.illuminant.code;
  d.color_matrix1 = c1.color_matrix;
  d.forward_matrix1 = c1.forward_matrix;
  d.has_forward_matrix1 = true;
  if (p2) {
    d.illuminant2 = c2.illuminant.code;
    d.color_matrix2 = c2.color_matrix;
    d.forward_matrix2 = c2.forward_matrix;
    d.has_color_matrix2 = d.has_forward_matrix2 = true;
  }
  if (map) {
    DcpHsvTable& t = d.hue_sat_map;
    t.hue = static_cast<std::uint32_t>(o.hue_sat_map[0]);
    t.sat = static_cast<std::uint32_t>(o.hue_sat_map[1]);
    t.val = static_cast<std::uint32_t>(o.hue_sat_map[2]);
    t.encoding = 0;
    t.data1 = hue_sat_data(*p1, c1, t.hue, t.sat, t.val, o.rgb_scale);
    if (p2) t.data2 = hue_sat_data(*p2, c2, t.hue, t.sat, t.val, o.rgb_scale);
  }
  if (o.linear_tone_curve) d.tone_curve = {0.f, 0.f, 1.f, 1.f};
  return d;
}

// ---------------------------------------------------------------------------- validation

namespace {

void check_table(const DcpHsvTable& t, const std::string& what, bool dual_data) {
  if (t.empty()) {
    if (!t.data1.empty() || !t.data2.empty())
      throw Error(ErrorCode::ProfileInvalid, what + " data without its dims");
    return;
  }
  check_dims(t.hue, t.sat, t.val, what, true);
  const std::size_t n = static_cast<std::size_t>(t.hue) * t.sat * t.val * 3;
  if (t.data1.empty()) throw Error(ErrorCode::ProfileInvalid, what + " dims without data (DNG 1.6: the data tag is required with the dims)");
  if (t.data1.size() != n || (!t.data2.empty() && t.data2.size() != n))
    throw Error(ErrorCode::ProfileInvalid, what + " data of " + std::to_string(t.data1.size()) + " floats where the dims need " +
                                               std::to_string(n));
  if (!t.data2.empty() && !dual_data)
    throw Error(ErrorCode::ProfileInvalid, what + " has a second table but the profile has no second illuminant");
  if (t.encoding > 1) throw Error(ErrorCode::ProfileInvalid, what + " encoding " + std::to_string(t.encoding) + " (0 linear, 1 sRGB)");
  for (const auto* data : {&t.data1, &t.data2})
    for (std::size_t i = 0; i < data->size(); ++i) {
      const float v = (*data)[i];
      if (!std::isfinite(v) || (i % 3 != 0 && v < 0))
        throw Error(ErrorCode::ProfileInvalid, what + ": entry " + std::to_string(i / 3) + " is not finite or has a negative scale");
    }
}

void check_matrix(const Mat3& m, const std::string& what) {
  if (!m.allFinite()) throw Error(ErrorCode::ProfileInvalid, what + " is not finite");
  if (!(std::abs(m.determinant()) > 1e-12)) throw Error(ErrorCode::ProfileInvalid, what + " is singular");
}

void check_text(const std::string& s, const std::string& what) {
  if (s.find('\0') != std::string::npos) throw Error(ErrorCode::ProfileInvalid, what + " contains a NUL byte");
}

void validate(const Dcp& d) {
  check_text(d.unique_camera_model, "UniqueCameraModel");
  check_text(d.profile_name, "ProfileName");
  check_text(d.copyright, "ProfileCopyright");
  check_text(d.calibration_signature, "ProfileCalibrationSignature");
  if (d.illuminant1 < 0 || d.illuminant1 > 65535 || d.illuminant2 < 0 || d.illuminant2 > 65535)
    throw Error(ErrorCode::ProfileInvalid, "a CalibrationIlluminant beyond a SHORT");
  check_matrix(d.color_matrix1, "ColorMatrix1");
  if (d.has_forward_matrix1) check_matrix(d.forward_matrix1, "ForwardMatrix1");
  if (d.has_color_matrix2) {
    if (d.illuminant2 == 0)
      throw Error(ErrorCode::ProfileInvalid, "ColorMatrix2 without CalibrationIlluminant2");
    check_matrix(d.color_matrix2, "ColorMatrix2");
    const double t1 = dcp_illuminant_temperature(d.illuminant1), t2 = dcp_illuminant_temperature(d.illuminant2);
    if (d.illuminant1 == d.illuminant2 || (t1 > 0 && t1 == t2))
      throw Error(ErrorCode::SameIlluminant, "CalibrationIlluminant1 " + fmt_code(d.illuminant1) + " and CalibrationIlluminant2 " +
                                                 fmt_code(d.illuminant2) +
                                                 " are the same (colour temperature): DNG readers use only the first");
  }
  if (d.has_forward_matrix2) {
    if (!d.has_forward_matrix1) throw Error(ErrorCode::ProfileInvalid, "ForwardMatrix2 without ForwardMatrix1");
    if (!d.has_color_matrix2) throw Error(ErrorCode::ProfileInvalid, "ForwardMatrix2 without ColorMatrix2");
    check_matrix(d.forward_matrix2, "ForwardMatrix2");
  }
  check_table(d.hue_sat_map, "ProfileHueSatMap", d.has_color_matrix2);
  check_table(d.look_table, "ProfileLookTable", false);
  if (!d.tone_curve.empty()) {
    if (d.tone_curve.size() < 4 || d.tone_curve.size() % 2 != 0)
      throw Error(ErrorCode::ProfileInvalid, "ProfileToneCurve needs x,y pairs, at least two");
    for (std::size_t i = 0; i < d.tone_curve.size(); ++i) {
      const float v = d.tone_curve[i];
      if (!std::isfinite(v) || v < 0 || v > 1 || (i >= 2 && i % 2 == 0 && !(v > d.tone_curve[i - 2])))
        throw Error(ErrorCode::ProfileInvalid, "ProfileToneCurve: points must be in [0, 1] with x increasing");
    }
  }
  if (d.embed_policy > 3) throw Error(ErrorCode::ProfileInvalid, "ProfileEmbedPolicy " + std::to_string(d.embed_policy) + " (0..3)");
  if (d.has_baseline_exposure_offset && !std::isfinite(d.baseline_exposure_offset))
    throw Error(ErrorCode::ProfileInvalid, "BaselineExposureOffset is not finite");
}

}  // namespace

// ---------------------------------------------------------------------------- writer

namespace {

struct Field {
  std::uint16_t tag, type;
  std::uint32_t count;
  std::vector<std::uint8_t> bytes;
};

void put16(std::vector<std::uint8_t>& b, std::uint32_t v) {
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  put16(b, v & 0xffff);
  put16(b, v >> 16);
}

Field ascii(std::uint16_t tag, const std::string& s) {
  Field f{tag, kAscii, static_cast<std::uint32_t>(s.size() + 1), {}};
  f.bytes.assign(s.begin(), s.end());
  f.bytes.push_back(0);
  return f;
}

Field longs(std::uint16_t tag, std::initializer_list<std::uint32_t> v) {
  Field f{tag, kLong, static_cast<std::uint32_t>(v.size()), {}};
  for (auto x : v) put32(f.bytes, x);
  return f;
}

Field floats(std::uint16_t tag, const std::vector<float>& v) {
  Field f{tag, kFloat, static_cast<std::uint32_t>(v.size()), {}};
  f.bytes.reserve(v.size() * 4);
  for (float x : v) {
    std::uint32_t u;
    std::memcpy(&u, &x, 4);
    put32(f.bytes, u);
  }
  return f;
}

/// SRATIONAL with the largest power-of-ten denominator <= 10^6 that keeps the numerator in range
/// (the DNG SDK rounds ColorMatrix to 10^-4 on reading only when it normalises it; 10^-6 keeps
/// ForwardMatrix·(1,1,1) = D50 to 2e-6).
Field srationals(std::uint16_t tag, const Mat3& m) {
  Field f{tag, kSRational, 9, {}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double v = m(r, c);
      std::int64_t den = 1000000;
      while (den > 1 && std::abs(std::llround(v * static_cast<double>(den))) > std::numeric_limits<std::int32_t>::max()) den /= 10;
      const std::int64_t num = std::llround(v * static_cast<double>(den));
      if (std::abs(num) > std::numeric_limits<std::int32_t>::max())
        throw Error(ErrorCode::ProfileInvalid, "a matrix entry " + std::to_string(v) + " beyond an SRATIONAL");
      put32(f.bytes, static_cast<std::uint32_t>(static_cast<std::int32_t>(num)));
      put32(f.bytes, static_cast<std::uint32_t>(den));
    }
  return f;
}

}  // namespace

std::vector<std::uint8_t> write_dcp(const Dcp& d) {
  validate(d);
  if (d.has_baseline_exposure_offset || d.has_default_black_render || !d.look_table.empty())
    throw Error(ErrorCode::InvalidArgument, "the DCP writer writes no LookTable, BaselineExposureOffset or DefaultBlackRender");
  std::vector<Field> fields;
  fields.push_back(ascii(dcp_tag::UniqueCameraModel, d.unique_camera_model));
  fields.push_back(srationals(dcp_tag::ColorMatrix1, d.color_matrix1));
  if (d.has_color_matrix2) fields.push_back(srationals(dcp_tag::ColorMatrix2, d.color_matrix2));
  Field ill1{dcp_tag::CalibrationIlluminant1, kShort, 1, {}};
  put16(ill1.bytes, static_cast<std::uint32_t>(d.illuminant1));
  fields.push_back(ill1);
  if (d.has_color_matrix2) {
    Field ill2{dcp_tag::CalibrationIlluminant2, kShort, 1, {}};
    put16(ill2.bytes, static_cast<std::uint32_t>(d.illuminant2));
    fields.push_back(ill2);
  }
  if (!d.calibration_signature.empty()) fields.push_back(ascii(dcp_tag::ProfileCalibrationSignature, d.calibration_signature));
  if (!d.profile_name.empty()) fields.push_back(ascii(dcp_tag::ProfileName, d.profile_name));
  if (!d.hue_sat_map.empty()) {
    // Dims and Data1 always together (RawTherapee reads the data tag after the dims unchecked).
    fields.push_back(longs(dcp_tag::ProfileHueSatMapDims, {d.hue_sat_map.hue, d.hue_sat_map.sat, d.hue_sat_map.val}));
    fields.push_back(floats(dcp_tag::ProfileHueSatMapData1, d.hue_sat_map.data1));
    if (!d.hue_sat_map.data2.empty()) fields.push_back(floats(dcp_tag::ProfileHueSatMapData2, d.hue_sat_map.data2));
    fields.push_back(longs(dcp_tag::ProfileHueSatMapEncoding, {d.hue_sat_map.encoding}));
  }
  if (!d.tone_curve.empty()) fields.push_back(floats(dcp_tag::ProfileToneCurve, d.tone_curve));
  fields.push_back(longs(dcp_tag::ProfileEmbedPolicy, {d.embed_policy}));
  if (!d.copyright.empty()) fields.push_back(ascii(dcp_tag::ProfileCopyright, d.copyright));
  if (d.has_forward_matrix1) fields.push_back(srationals(dcp_tag::ForwardMatrix1, d.forward_matrix1));
  if (d.has_forward_matrix2) fields.push_back(srationals(dcp_tag::ForwardMatrix2, d.forward_matrix2));
  std::sort(fields.begin(), fields.end(), [](const Field& a, const Field& b) { return a.tag < b.tag; });

  // Header, the IFD at offset 8, then every value longer than 4 bytes at an even offset (TIFF 6.0
  // §2: values begin on a word boundary).
  std::vector<std::uint8_t> out = {'I', 'I', 'R', 'C'};
  put32(out, 8);
  const std::size_t ifd_end = 8 + 2 + 12 * fields.size() + 4;
  std::vector<std::uint8_t> data;
  put16(out, static_cast<std::uint32_t>(fields.size()));
  for (const Field& f : fields) {
    put16(out, f.tag);
    put16(out, f.type);
    put32(out, f.count);
    if (f.bytes.size() <= 4) {
      std::vector<std::uint8_t> v = f.bytes;
      v.resize(4, 0);
      out.insert(out.end(), v.begin(), v.end());
    } else {
      if (data.size() % 2) data.push_back(0);
      const std::size_t at = ifd_end + data.size();
      if (at + f.bytes.size() > std::numeric_limits<std::uint32_t>::max())
        throw Error(ErrorCode::ExportFailed, "DCP larger than 4 GB");
      put32(out, static_cast<std::uint32_t>(at));
      data.insert(data.end(), f.bytes.begin(), f.bytes.end());
    }
  }
  put32(out, 0);  // no next IFD
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

// ---------------------------------------------------------------------------- reader

bool is_dcp(const std::uint8_t* b, std::size_t n) {
  return n >= 4 && ((b[0] == 'I' && b[1] == 'I' && b[2] == 'R' && b[3] == 'C') ||
                    (b[0] == 'M' && b[1] == 'M' && b[2] == 'C' && b[3] == 'R'));
}

namespace {

struct Reader {
  const std::uint8_t* b;
  std::size_t n;
  bool le;
  std::uint32_t u16(std::size_t at) const {
    if (at + 2 > n) throw Error(ErrorCode::ParseError, "DCP: truncated at byte " + std::to_string(at));
    return le ? (b[at] | b[at + 1] << 8) : (b[at] << 8 | b[at + 1]);
  }
  std::uint32_t u32(std::size_t at) const {
    const std::uint32_t x = u16(at), y = u16(at + 2);
    return le ? (x | y << 16) : (x << 16 | y);
  }
};

struct Entry {
  std::uint16_t type;
  std::uint32_t count;
  std::size_t at;  // where the values are
};

const char* tag_name(std::uint16_t tag) {
  switch (tag) {
    case dcp_tag::UniqueCameraModel: return "UniqueCameraModel";
    case dcp_tag::ColorMatrix1: return "ColorMatrix1";
    case dcp_tag::ColorMatrix2: return "ColorMatrix2";
    case dcp_tag::CalibrationIlluminant1: return "CalibrationIlluminant1";
    case dcp_tag::CalibrationIlluminant2: return "CalibrationIlluminant2";
    case dcp_tag::ProfileCalibrationSignature: return "ProfileCalibrationSignature";
    case dcp_tag::ProfileName: return "ProfileName";
    case dcp_tag::ProfileHueSatMapDims: return "ProfileHueSatMapDims";
    case dcp_tag::ProfileHueSatMapData1: return "ProfileHueSatMapData1";
    case dcp_tag::ProfileHueSatMapData2: return "ProfileHueSatMapData2";
    case dcp_tag::ProfileToneCurve: return "ProfileToneCurve";
    case dcp_tag::ProfileEmbedPolicy: return "ProfileEmbedPolicy";
    case dcp_tag::ProfileCopyright: return "ProfileCopyright";
    case dcp_tag::ForwardMatrix1: return "ForwardMatrix1";
    case dcp_tag::ForwardMatrix2: return "ForwardMatrix2";
    case dcp_tag::ProfileLookTableDims: return "ProfileLookTableDims";
    case dcp_tag::ProfileLookTableData: return "ProfileLookTableData";
    case dcp_tag::ProfileHueSatMapEncoding: return "ProfileHueSatMapEncoding";
    case dcp_tag::ProfileLookTableEncoding: return "ProfileLookTableEncoding";
    case dcp_tag::BaselineExposureOffset: return "BaselineExposureOffset";
    case dcp_tag::DefaultBlackRender: return "DefaultBlackRender";
    default: return nullptr;
  }
}

}  // namespace

Dcp read_dcp(const std::uint8_t* b, std::size_t n) {
  if (n == 0) throw Error(ErrorCode::EmptyFile, "DCP: empty file");
  if (n < 8 || !is_dcp(b, n))
    throw Error(ErrorCode::ParseError, "not a DCP: a DNG camera profile starts with \"IIRC\" or \"MMCR\" (DNG 1.6 chapter 7)");
  const Reader r{b, n, b[0] == 'I'};
  const std::size_t ifd = r.u32(4);
  if (ifd < 8 || ifd + 2 > n) throw Error(ErrorCode::ParseError, "DCP: the IFD offset " + std::to_string(ifd) + " is outside the file");
  const std::uint32_t count = r.u16(ifd);
  if (count == 0) throw Error(ErrorCode::ParseError, "DCP: an empty IFD");
  if (ifd + 2 + 12 * static_cast<std::size_t>(count) > n)
    throw Error(ErrorCode::ParseError, "DCP: the IFD's " + std::to_string(count) + " entries run past the end of the file");
  std::map<std::uint16_t, Entry> entries;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t e = ifd + 2 + 12 * static_cast<std::size_t>(i);
    const auto tag = static_cast<std::uint16_t>(r.u16(e));
    const auto type = static_cast<std::uint16_t>(r.u16(e + 2));
    const std::uint32_t cnt = r.u32(e + 4);
    const char* name = tag_name(tag);
    if (!name) continue;  // another tag: not ours to judge
    const std::size_t size = type_size(type);
    if (size == 0) throw Error(ErrorCode::ParseError, std::string("DCP: ") + name + " has an unknown type " + std::to_string(type));
    const std::uint64_t bytes = static_cast<std::uint64_t>(cnt) * size;
    const std::size_t at = bytes <= 4 ? e + 8 : r.u32(e + 8);
    if (bytes > n || at > n - bytes)
      throw Error(ErrorCode::ParseError, std::string("DCP: ") + name + "'s " + std::to_string(cnt) + " values lie outside the file");
    if (entries.count(tag)) throw Error(ErrorCode::ParseError, std::string("DCP: ") + name + " appears twice");
    entries[tag] = Entry{type, cnt, at};
  }
  auto find = [&](std::uint16_t tag) -> const Entry* {
    auto it = entries.find(tag);
    return it == entries.end() ? nullptr : &it->second;
  };
  auto want = [&](std::uint16_t tag, const Entry& e, std::initializer_list<std::uint16_t> types, std::uint32_t cnt) {
    if (std::find(types.begin(), types.end(), e.type) == types.end())
      throw Error(ErrorCode::ParseError, std::string("DCP: ") + tag_name(tag) + " has type " + std::to_string(e.type));
    if (cnt && e.count != cnt)
      throw Error(ErrorCode::ParseError, std::string("DCP: ") + tag_name(tag) + " has " + std::to_string(e.count) +
                                             " values, not " + std::to_string(cnt));
  };
  auto text = [&](std::uint16_t tag) -> std::string {
    const Entry* e = find(tag);
    if (!e) return "";
    want(tag, *e, {kAscii, kByte}, 0);  // DNG 1.6 allows BYTE (UTF-8) for the profile strings
    std::string s(reinterpret_cast<const char*>(b + e->at), e->count);
    while (!s.empty() && s.back() == '\0') s.pop_back();
    if (s.find('\0') != std::string::npos) s.resize(s.find('\0'));
    return s;
  };
  auto whole = [&](std::uint16_t tag, std::uint32_t fallback) -> std::uint32_t {
    const Entry* e = find(tag);
    if (!e) return fallback;
    want(tag, *e, {kShort, kLong}, 1);
    return e->type == kShort ? r.u16(e->at) : r.u32(e->at);
  };
  auto rational = [&](std::size_t at, bool is_signed, const char* name) {
    const std::uint32_t a = r.u32(at), d = r.u32(at + 4);
    const double num = is_signed ? static_cast<double>(static_cast<std::int32_t>(a)) : a;
    const double den = is_signed ? static_cast<double>(static_cast<std::int32_t>(d)) : d;
    if (den == 0) throw Error(ErrorCode::ProfileInvalid, std::string("DCP: ") + name + " has a zero denominator");
    return num / den;
  };
  auto matrix = [&](std::uint16_t tag, bool& present) {
    Mat3 m = Mat3::Identity();
    const Entry* e = find(tag);
    present = e != nullptr;
    if (!e) return m;
    want(tag, *e, {kSRational, kRational}, 0);
    if (e->count != 9)
      throw Error(ErrorCode::ProfileInvalid, std::string("DCP: ") + tag_name(tag) + " has " + std::to_string(e->count) +
                                                 " values: only 3-colour cameras (9 values) are supported");
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = rational(e->at + 8 * i, e->type == kSRational, tag_name(tag));
    return m;
  };
  auto float_array = [&](std::uint16_t tag) {
    std::vector<float> v;
    const Entry* e = find(tag);
    if (!e) return v;
    want(tag, *e, {kFloat}, 0);
    v.resize(e->count);
    for (std::uint32_t i = 0; i < e->count; ++i) {
      const std::uint32_t u = r.u32(e->at + 4 * static_cast<std::size_t>(i));
      std::memcpy(&v[i], &u, 4);
    }
    return v;
  };
  auto dims = [&](std::uint16_t tag, DcpHsvTable& t) {
    const Entry* e = find(tag);
    if (!e) return;
    want(tag, *e, {kLong}, 3);
    t.hue = r.u32(e->at);
    t.sat = r.u32(e->at + 4);
    t.val = r.u32(e->at + 8);
    if (t.hue == 0) throw Error(ErrorCode::ProfileInvalid, std::string("DCP: ") + tag_name(tag) + " has 0 hue divisions");
  };

  Dcp d;
  d.unique_camera_model = text(dcp_tag::UniqueCameraModel);
  d.profile_name = text(dcp_tag::ProfileName);
  d.copyright = text(dcp_tag::ProfileCopyright);
  d.calibration_signature = text(dcp_tag::ProfileCalibrationSignature);
  d.embed_policy = whole(dcp_tag::ProfileEmbedPolicy, 0);
  d.illuminant1 = static_cast<int>(whole(dcp_tag::CalibrationIlluminant1, 0));
  d.illuminant2 = static_cast<int>(whole(dcp_tag::CalibrationIlluminant2, 0));
  bool has_cm1 = false;
  d.color_matrix1 = matrix(dcp_tag::ColorMatrix1, has_cm1);
  if (!has_cm1) throw Error(ErrorCode::ProfileInvalid, "DCP without ColorMatrix1 (DNG 1.6: every camera profile has one)");
  d.color_matrix2 = matrix(dcp_tag::ColorMatrix2, d.has_color_matrix2);
  d.forward_matrix1 = matrix(dcp_tag::ForwardMatrix1, d.has_forward_matrix1);
  d.forward_matrix2 = matrix(dcp_tag::ForwardMatrix2, d.has_forward_matrix2);
  dims(dcp_tag::ProfileHueSatMapDims, d.hue_sat_map);
  d.hue_sat_map.data1 = float_array(dcp_tag::ProfileHueSatMapData1);
  d.hue_sat_map.data2 = float_array(dcp_tag::ProfileHueSatMapData2);
  d.hue_sat_map.encoding = whole(dcp_tag::ProfileHueSatMapEncoding, 0);
  dims(dcp_tag::ProfileLookTableDims, d.look_table);
  d.look_table.data1 = float_array(dcp_tag::ProfileLookTableData);
  d.look_table.encoding = whole(dcp_tag::ProfileLookTableEncoding, 0);
  d.tone_curve = float_array(dcp_tag::ProfileToneCurve);
  if (const Entry* e = find(dcp_tag::BaselineExposureOffset)) {
    want(dcp_tag::BaselineExposureOffset, *e, {kSRational}, 1);
    d.has_baseline_exposure_offset = true;
    d.baseline_exposure_offset = rational(e->at, true, "BaselineExposureOffset");
  }
  if (find(dcp_tag::DefaultBlackRender)) {
    d.has_default_black_render = true;
    d.default_black_render = whole(dcp_tag::DefaultBlackRender, 0);
  }
  if (d.has_color_matrix2 && !find(dcp_tag::CalibrationIlluminant2))
    throw Error(ErrorCode::ProfileInvalid, "DCP: ColorMatrix2 without CalibrationIlluminant2");
  validate(d);
  return d;
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

Vec3 dcp_render(const Dcp& d, const DcpTransform& t, const Vec3& camera_rgb, bool use_map) {
  Vec3 xyz = t.camera_to_xyz * camera_rgb;
  const DcpHsvTable& m = d.hue_sat_map;
  if (!use_map || m.empty()) return xyz;
  const Mat3 pp = prophoto_to_xyz();
  const Vec3 rgb = pp.inverse() * xyz;
  if (!rgb.allFinite() || rgb.minCoeff() < 0) return xyz;  // RawTherapee leaves colours outside ProPhoto to the matrix
  Vec3 hsv = rgb_to_hsv(rgb);
  const double g = m.data2.empty() ? 1.0 : t.weight1;
  auto entry = [&](std::size_t vi, std::size_t hi, std::size_t si, int k) {
    const std::size_t i = 3 * ((vi * m.hue + hi) * m.sat + si) + k;
    return g * m.data1[i] + (m.data2.empty() ? 0.0 : (1 - g) * m.data2[i]);
  };
  // The DNG SDK's RefBaselineHueSatMap: hue wraps, saturation and value indices clamped to the
  // table (their fractions are not), trilinear.
  const double hs = m.hue < 2 ? 0.0 : hsv[0] / 360.0 * m.hue, ss = hsv[1] * (m.sat - 1);
  std::size_t h0 = static_cast<std::size_t>(std::max(0.0, hs)), h1 = h0 + 1;
  if (h0 >= m.hue - 1) {
    h0 = m.hue - 1;
    h1 = 0;
  }
  const std::size_t s0 = std::min<std::size_t>(static_cast<std::size_t>(ss), m.sat - 2);
  const double hf = hs - h0, sf = ss - s0;
  double v_lookup = hsv[2];
  if (m.encoding == 1) v_lookup = sRGB_encode(std::min(1.0, v_lookup));
  const double vs = m.val < 2 ? 0.0 : std::min(v_lookup * (m.val - 1), static_cast<double>(m.val));
  const std::size_t v0 = m.val < 2 ? 0 : std::min<std::size_t>(static_cast<std::size_t>(std::max(0.0, vs)), m.val - 2);
  const std::size_t v1 = m.val < 2 ? 0 : v0 + 1;
  const double vf = m.val < 2 ? 0.0 : vs - v0;
  double delta[3];
  for (int k = 0; k < 3; ++k) {
    auto at_v = [&](std::size_t vi) {
      const double a = (1 - sf) * entry(vi, h0, s0, k) + sf * entry(vi, h0, s0 + 1, k);
      const double b = (1 - sf) * entry(vi, h1, s0, k) + sf * entry(vi, h1, s0 + 1, k);
      return (1 - hf) * a + hf * b;
    };
    delta[k] = (1 - vf) * at_v(v0) + vf * at_v(v1);
  }
  hsv[0] += delta[0];
  hsv[1] *= delta[1];
  hsv[2] *= delta[2];
  return pp * hsv_to_rgb(hsv);
}

// ---------------------------------------------------------------------------- JSON

json::Value dcp_json(const Dcp& d) {
  auto mat = [](const Mat3& m) {
    json::Value a = json::Value::array();
    for (int r = 0; r < 3; ++r) a.push(std::vector<double>{m(r, 0), m(r, 1), m(r, 2)});
    return a;
  };
  auto illum = [](int code) {
    json::Value o = json::Value::object();
    o.set("code", code);
    o.set("name", dcp_illuminant_name(code));
    o.set("temperature", dcp_illuminant_temperature(code));
    return o;
  };
  auto table = [](const DcpHsvTable& t) {
    json::Value o = json::Value::object();
    o.set("dims", std::vector<double>{double(t.hue), double(t.sat), double(t.val)});
    o.set("encoding", t.encoding == 1 ? "sRGB" : "linear");
    o.set("tables", t.data2.empty() ? 1 : 2);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto* data : {&t.data1, &t.data2})
      for (std::size_t i = 0; i < data->size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], double((*data)[i]));
        hi[i % 3] = std::max(hi[i % 3], double((*data)[i]));
      }
    o.set("hue_shift_range", std::vector<double>{lo[0], hi[0]});
    o.set("sat_scale_range", std::vector<double>{lo[1], hi[1]});
    o.set("val_scale_range", std::vector<double>{lo[2], hi[2]});
    return o;
  };
  json::Value o = json::Value::object();
  o.set("format", "dcp");
  o.set("unique_camera_model", d.unique_camera_model);
  o.set("profile_name", d.profile_name);
  o.set("copyright", d.copyright);
  o.set("calibration_signature", d.calibration_signature);
  static const char* policies[] = {"allow copying", "embed if used", "never embed", "no restrictions"};
  o.set("embed_policy", d.embed_policy <= 3 ? policies[d.embed_policy] : "unknown");
  json::Value ills = json::Value::array();
  ills.push(illum(d.illuminant1));
  if (d.dual()) ills.push(illum(d.illuminant2));
  o.set("illuminants", ills);
  o.set("color_matrix1", mat(d.color_matrix1));
  if (d.has_color_matrix2) o.set("color_matrix2", mat(d.color_matrix2));
  if (d.has_forward_matrix1) o.set("forward_matrix1", mat(d.forward_matrix1));
  if (d.has_forward_matrix2) o.set("forward_matrix2", mat(d.forward_matrix2));
  if (!d.hue_sat_map.empty()) o.set("hue_sat_map", table(d.hue_sat_map));
  if (!d.look_table.empty()) o.set("look_table", table(d.look_table));
  if (!d.tone_curve.empty()) o.set("tone_curve_points", static_cast<int>(d.tone_curve.size() / 2));
  if (d.has_baseline_exposure_offset) o.set("baseline_exposure_offset", d.baseline_exposure_offset);
  if (d.has_default_black_render) o.set("default_black_render", static_cast<int>(d.default_black_render));
  // Per calibration illuminant: the camera neutral its ColorMatrix gives the illuminant's white,
  // and what the reader's pipeline (this file's dcp_camera_to_xyz) renders that neutral as; a
  // consistent profile renders it as D50 (xy 0.3457, 0.3585).
  json::Value checks = json::Value::array();
  for (int k = 1; k <= (d.dual() ? 2 : 1); ++k) {
    const int code = k == 1 ? d.illuminant1 : d.illuminant2;
    json::Value c = json::Value::object();
    c.set("illuminant", code);
    const DcpIlluminant* row = nullptr;
    for (const auto& r : dcp_illuminants())
      if (r.code == code) {
        row = &r;
        break;
      }
    if (row) {
      const Mat3& cm = k == 1 ? d.color_matrix1 : d.color_matrix2;
      Vec3 n = cm * xy_to_XYZ(row->x, row->y);
      if (n.minCoeff() > 0) {
        n /= n.maxCoeff();
        c.set("neutral", std::vector<double>{n[0], n[1], n[2]});
        const DcpTransform t = dcp_camera_to_xyz(d, n, k);
        const Vec3 xyz = t.camera_to_xyz * n;
        const Eigen::Vector2d xy = XYZ_to_xy(xyz);
        c.set("white_xy", std::vector<double>{t.white_xy[0], t.white_xy[1]});
        c.set("neutral_renders_as_xy", std::vector<double>{xy[0], xy[1]});
        c.set("neutral_renders_as_Y", xyz[1]);
      } else {
        c.set("neutral", "not positive: the ColorMatrix does not map the illuminant's white into the camera's range");
      }
    }
    checks.push(c);
  }
  o.set("checks", checks);
  return o;
}

}  // namespace tristim

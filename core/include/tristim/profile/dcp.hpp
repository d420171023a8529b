// DNG Camera Profiles (.dcp): a profile's colour as raw converters load it (Adobe Camera Raw and
// Lightroom, RawTherapee, darktable's DNG path …).
//
// The file (Adobe DNG Specification 1.6.0.0, chapter 7 "DNG Camera Profile File Format") is a
// TIFF structure whose magic is "IIRC" (little-endian) or "MMCR" (big-endian) in place of
// "II*\0"; one IFD holds the camera profile tags of chapter 4, here:
//   UniqueCameraModel 50708 ASCII        CalibrationIlluminant1/2 50778/50779 SHORT
//   ColorMatrix1/2 50721/50722 SRATIONAL×9 (XYZ under the illuminant -> camera native RGB)
//   ForwardMatrix1/2 50964/50965 SRATIONAL×9 (white-balanced camera RGB -> XYZ D50)
//   ProfileCalibrationSignature 50932 ASCII  ProfileName 50936 ASCII  ProfileCopyright 50942 ASCII
//   ProfileEmbedPolicy 50941 LONG        ProfileHueSatMapDims 50937 LONG×3
//   ProfileHueSatMapData1/2 50938/50939 FLOAT×(3·H·S·V)  ProfileHueSatMapEncoding 51107 LONG
//   ProfileToneCurve 50940 FLOAT×2n      ProfileLookTableDims/Data/Encoding 50981/50982/51108 (read only)
//   BaselineExposureOffset 51109 SRATIONAL, DefaultBlackRender 51110 LONG (read only)
// (numbers and types as in the specification and in exiftool 12.57's tag table).
//
// From a tristim profile (a camera RGB -> XYZ model fitted under a reference illuminant):
//   w      the camera RGB of the perfect diffuser: model(w) = the profile white (Newton's method for
//          a non-linear model); the camera neutral is w / max(w).
//   J      the model's matrix: M for a 3×3 model, the Jacobian at w for any other (its linear part
//          at neutral; for an exposure-invariant model J·w = model(w), so the white stays exact).
//   ForwardMatrix = Bradford(profile white -> D50)·J·diag(w), rows scaled so that
//          ForwardMatrix·(1,1,1) = D50 (xy 0.3457, 0.3585, the DNG SDK's PCS white): §6 "Camera to
//          XYZ (D50) Transform" with camera neutral as the white balance.
//   ColorMatrix   = (Bradford(profile white -> illuminant)·J)⁻¹, scaled so that its largest
//          component of ColorMatrix·XYZ(illuminant, Y = 1) is 1: it maps the calibration
//          illuminant's white to the camera neutral (the normalisation of the DNG SDK's camera white).
//   HueSatMap (optional): at every node (hue, saturation, value) of the linear ProPhoto HSV grid
//          the change from what ForwardMatrix renders to what the model renders for the same
//          camera RGB (§6 "Applying the Hue/Saturation/Value Mapping Table").
// A dual-illuminant DCP takes one profile per illuminant (the same camera); illuminant 1 is the
// one of lower colour temperature, as the DNG SDK interpolates between them in inverse CCT.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/io/json.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim {

/// Tag numbers of the camera profile tags (DNG 1.6 chapter 4 and 6).
namespace dcp_tag {
constexpr std::uint16_t UniqueCameraModel = 50708;
constexpr std::uint16_t ColorMatrix1 = 50721;
constexpr std::uint16_t ColorMatrix2 = 50722;
constexpr std::uint16_t CalibrationIlluminant1 = 50778;
constexpr std::uint16_t CalibrationIlluminant2 = 50779;
constexpr std::uint16_t ProfileCalibrationSignature = 50932;
constexpr std::uint16_t ProfileName = 50936;
constexpr std::uint16_t ProfileHueSatMapDims = 50937;
constexpr std::uint16_t ProfileHueSatMapData1 = 50938;
constexpr std::uint16_t ProfileHueSatMapData2 = 50939;
constexpr std::uint16_t ProfileToneCurve = 50940;
constexpr std::uint16_t ProfileEmbedPolicy = 50941;
constexpr std::uint16_t ProfileCopyright = 50942;
constexpr std::uint16_t ForwardMatrix1 = 50964;
constexpr std::uint16_t ForwardMatrix2 = 50965;
constexpr std::uint16_t ProfileLookTableDims = 50981;
constexpr std::uint16_t ProfileLookTableData = 50982;
constexpr std::uint16_t ProfileHueSatMapEncoding = 51107;
constexpr std::uint16_t ProfileLookTableEncoding = 51108;
constexpr std::uint16_t BaselineExposureOffset = 51109;
constexpr std::uint16_t DefaultBlackRender = 51110;
}  // namespace dcp_tag

/// A calibration illuminant tristim can write: its EXIF LightSource code (DNG 1.6
/// CalibrationIlluminant1), tristim's illuminant id, the DNG SDK's temperature for the code (what
/// readers interpolate with) and the chromaticity the matrices are built for.
struct DcpIlluminant {
  int code;
  std::string id;    ///< tristim's illuminant id (illuminant_spd)
  std::string name;  ///< the LightSource name (exiftool's spelling)
  double temperature;
  double x, y;
};
/// A 17, F2 and F11 14 (cool white fluorescent, 3800–4500 K), D50 23, D55 20, D65 21, D75 22.
const std::vector<DcpIlluminant>& dcp_illuminants();
/// The row of a tristim illuminant id; Error(UnknownId) naming the ones a DCP can carry.
const DcpIlluminant& dcp_illuminant(const std::string& id);
/// The LightSource name of any code ("" for an unknown one).
std::string dcp_illuminant_name(int code);
/// The DNG SDK's temperature of any LightSource code (0 when it has none: unknown, other).
double dcp_illuminant_temperature(int code);

/// A Hue/Saturation/Value mapping table (ProfileHueSatMap* or ProfileLookTable*): per node the
/// hue shift (degrees), saturation scale and value scale, saturation fastest, then hue, then value.
struct DcpHsvTable {
  std::uint32_t hue = 0, sat = 0, val = 0;  ///< divisions (all 0: absent)
  std::uint32_t encoding = 0;               ///< 0 linear value axis, 1 sRGB-encoded
  std::vector<float> data1, data2;          ///< 3·hue·sat·val floats each (data2: dual-illuminant)
  bool empty() const { return hue == 0; }
};

/// The contents of a DCP (what write_dcp writes and read_dcp reads).
struct Dcp {
  std::string unique_camera_model;
  std::string profile_name;
  std::string copyright;
  std::string calibration_signature;
  std::uint32_t embed_policy = 0;  ///< 0 allow copying, 1 embed if used, 2 never embed, 3 no restrictions
  int illuminant1 = 0, illuminant2 = 0;  ///< LightSource codes (illuminant2 0: single-illuminant)
  Mat3 color_matrix1 = Mat3::Identity(), color_matrix2 = Mat3::Identity();
  Mat3 forward_matrix1 = Mat3::Identity(), forward_matrix2 = Mat3::Identity();
  bool has_color_matrix2 = false, has_forward_matrix1 = false, has_forward_matrix2 = false;
  DcpHsvTable hue_sat_map;
  DcpHsvTable look_table;          ///< read only (data1); tristim never writes one
  std::vector<float> tone_curve;   ///< x0, y0, x1, y1 … (empty: none)
  bool has_baseline_exposure_offset = false;
  double baseline_exposure_offset = 0;
  bool has_default_black_render = false;
  std::uint32_t default_black_render = 0;
  bool dual() const { return has_color_matrix2; }
};

/// How a tristim profile becomes a DCP.
struct DcpOptions {
  std::string camera_model;  ///< UniqueCameraModel (required: the profile JSON names no camera)
  std::string profile_name;  ///< "" -> "tristim <model> <objective> <illuminant>[ + …]"
  std::string copyright;     ///< "" -> "Generated by tristim <version>; no copyright asserted"
  std::uint32_t embed_policy = 0;
  /// Calibration illuminant of the first / second profile (a dcp_illuminants() id); "" takes the
  /// profile's own: its recipe's reference illuminant, else its "illuminant" field.
  std::string illuminant, second_illuminant;
  /// HueSatMap divisions (hue, saturation, value); all 0: none. Hue 1..360, saturation 2..256,
  /// value 1..256, at most 2,000,000 nodes.
  std::array<int, 3> hue_sat_map{0, 0, 0};
  /// Camera value (DN) of DNG value 1.0 on the value axis of the HueSatMap (0: the profile's
  /// rgb_max); it matters only for a model that is not exposure-invariant.
  double rgb_scale = 0;
  bool linear_tone_curve = false;  ///< write ProfileToneCurve (0,0)-(1,1) (else none: the reader's default)
};

/// The ColorMatrix, ForwardMatrix, neutral and calibration illuminant derived from one profile.
struct DcpCalibration {
  DcpIlluminant illuminant;
  Vec3 camera_white;   ///< w: the model's camera RGB of the profile white (DN)
  Vec3 neutral;        ///< w / max(w)
  Mat3 linear;         ///< J: camera RGB -> XYZ (the profile's units) at neutral
  Mat3 color_matrix;   ///< XYZ under the illuminant (Y = 1) -> camera neutral scale
  Mat3 forward_matrix; ///< white-balanced camera RGB -> XYZ D50, rows summing to D50
};
/// Error(InvalidArgument) for a profile that takes stored (non-linear) values: a DCP applies to
/// linear RAW data; Error(ProfileInvalid) when the model has no positive camera white.
DcpCalibration dcp_calibration(const Profile& profile, const std::string& illuminant_id = "");
/// The calibration illuminant id a profile states (see DcpOptions::illuminant).
std::string profile_illuminant_id(const Profile& profile);

/// The DCP of one profile (single-illuminant) or of two profiles of the same camera under two
/// different illuminants. Error(SameIlluminant) for equal illuminants, Error(InvalidArgument)
/// for options out of range or a missing camera model, UnknownId for an illuminant no LightSource
/// code names.
Dcp make_dcp(const Profile& first, const DcpOptions& options, const Profile* second = nullptr);

/// The file: "IIRC", one IFD with the tags in ascending order, values after it, word aligned.
/// Error(ProfileInvalid) for a Dcp that breaks the rules read_dcp checks.
std::vector<std::uint8_t> write_dcp(const Dcp& dcp);

/// Strict reader ("IIRC" or "MMCR"). Error(ParseError) for a broken TIFF structure (magic,
/// offsets and counts outside the file, a tag of the wrong type or count); Error(ProfileInvalid)
/// for a DCP without ColorMatrix1 or CalibrationIlluminant1, HueSatMap dims without data (or
/// data without dims, or of the wrong length), a second matrix without a second illuminant, a
/// non-finite value; Error(SameIlluminant) for two equal illuminants; Error(LimitExceeded) for
/// tables beyond the writer's limits.
Dcp read_dcp(const std::uint8_t* bytes, std::size_t size);
inline Dcp read_dcp(const std::vector<std::uint8_t>& b) { return read_dcp(b.data(), b.size()); }
/// Whether bytes start like a DCP ("IIRC" / "MMCR").
bool is_dcp(const std::uint8_t* bytes, std::size_t size);

/// Every tag as JSON (matrices row by row, illuminants with their names, the tables' dims and
/// ranges), plus the reference renderer's checks: per illuminant the white its neutral maps to.
json::Value dcp_json(const Dcp& dcp);

// --- the DNG pipeline of chapter 6, as a reference for tests and checks --------------------

/// The D50 PCS white of the DNG SDK (xy 0.3457, 0.3585, Y = 1).
Vec3 dcp_d50();
/// XYZ (D50) <- linear ProPhoto (ROMM) RGB, the DNG SDK's matrix.
Mat3 prophoto_to_xyz();

/// The camera -> XYZ D50 matrix a DNG reader uses for a camera neutral (AsShotNeutral), with the
/// weight of illuminant 1 and the white chromaticity it found: §6 "Translating White Balance xy
/// Coordinates to/from Camera Neutral Coordinates" (iterated as the DNG SDK does) and
/// "Camera to XYZ (D50) Transform" (ForwardMatrix when present, else ColorMatrix with Bradford
/// adaptation to D50). `illuminant`: 0 interpolate, 1 or 2 use that one only.
struct DcpTransform {
  Mat3 camera_to_xyz;
  double weight1 = 1;
  Eigen::Vector2d white_xy;
};
DcpTransform dcp_camera_to_xyz(const Dcp& dcp, const Vec3& camera_neutral, int illuminant = 0);
/// XYZ D50 of camera RGB (DNG units: 1 = white level) through the transform and, with
/// `hue_sat_map`, the HueSatMap in linear ProPhoto HSV as the DNG SDK's RefBaselineHueSatMap and
/// RawTherapee apply it: trilinear, hue wrapping, saturation and value indices held to the table
/// (their fractions extrapolate), the result not clipped; a colour outside ProPhoto (a negative
/// component) keeps the matrix alone, as in RawTherapee.
Vec3 dcp_render(const Dcp& dcp, const DcpTransform& t, const Vec3& camera_rgb, bool hue_sat_map = true);

}  // namespace tristim

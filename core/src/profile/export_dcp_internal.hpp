// Shared by the DCP sources (export_dcp.cpp, export_dcp_matrices.cpp, export_dcp_hue_sat_map.cpp,
// export_dcp_tiff.cpp); not a public header (profile/dcp.hpp is).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/profile/dcp.hpp"

namespace tristim::dcp_internal {

// Limits of the HueSatMap/LookTable dims, written and read (DcpOptions::hue_sat_map).
constexpr std::uint32_t kMaxHue = 360, kMaxSat = 256, kMaxVal = 256;
constexpr std::uint64_t kMaxNodes = 2000000;

/// "17 (Standard Light A)": a LightSource code with its name, for messages.
std::string fmt_code(int code);

inline Vec3 xy_to_XYZ(double x, double y) { return Vec3(x / y, 1.0, (1.0 - x - y) / y); }

/// Hexcone HSV with hue in degrees [0, 360), as the DNG SDK's DNG_RGBtoHSV (hue in sixths there).
Vec3 rgb_to_hsv(const Vec3& rgb);
Vec3 hsv_to_rgb(const Vec3& hsv);

/// The HueSatMap of one profile against its forward matrix: per node of the ProPhoto HSV grid,
/// what turns the ForwardMatrix's rendering of a camera RGB into the model's (hue shift in
/// degrees, saturation and value scales). Nodes whose camera RGB would be negative (outside
/// what a camera records) hold the correction of the last valid saturation at their hue.
std::vector<float> hue_sat_data(const Profile& p, const DcpCalibration& c, std::uint32_t H, std::uint32_t S,
                                std::uint32_t V, double rgb_scale);
/// Error(InvalidArgument) when writing, ProfileInvalid / LimitExceeded when reading, for dims
/// beyond DNG 1.6 or the writer's limits.
void check_dims(std::uint32_t h, std::uint32_t s, std::uint32_t v, const std::string& what, bool reading);

/// The rules read_dcp checks and write_dcp keeps (Error(ProfileInvalid), SameIlluminant).
void validate(const Dcp& d);

}  // namespace tristim::dcp_internal

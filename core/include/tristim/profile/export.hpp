// Exports of a profile for other tools: ICC v4 input profile (lcms2), .cube 3D LUT, per-patch
// CSV; and 32-bit float image files (TIFF, PFM) for XYZ images.
//
// Device encoding of the ICC and .cube exports: device value d = camera RGB / rgb_scale
// (default: the profile's training rgb_max), so d = 1 is the brightest training value.
// Output: XYZ relative to the profile's white (white Y -> 1). The ICC PCS is D50: when the
// profile white is not D50, XYZ is adapted with Bradford and a 'chad' tag records it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim {

struct IccOptions {
  double rgb_scale = 0;       ///< 0: profile.rgb_max
  int grid_points = 33;       ///< CLUT grid of LUT-based profiles (2..255)
  double shaper_gamma = 2.2;  ///< A-curve of LUT profiles: grid is uniform in d^(1/gamma)
  std::string description;    ///< empty: "tristim <model> (<objective>)"
  /// ICC version: 4.3 (default) or 2.4 (for readers without v4 support, e.g. Argyll 2.3's
  /// icclib; AToB0 then is a lut16Type and the white is not written as D50 but the same way).
  double version = 4.3;
};

/// ICC v4.3 input-class RGB -> PCS XYZ profile. A plain 3×3 model gives a matrix/shaper
/// profile (rXYZ/gXYZ/bXYZ + identity TRCs); every other model an AToB0 lutAtoBType with
/// A curves (gamma 1/shaper_gamma), a 16-bit CLUT sampled from the model, identity B curves.
/// Error(ExportFailed) if lcms2 refuses.
std::vector<uint8_t> export_icc(const Profile& profile, const IccOptions& options = {});

/// Runs an ICC profile (bytes) through lcms2: device RGB (0..1, N × 3) -> PCS XYZ (D50, Y=1),
/// relative colorimetric. For checks and tests.
PatchMatrix icc_device_to_XYZ(const std::vector<uint8_t>& icc, const PatchMatrix& device_RGB);

/// .cube (Adobe/Resolve 3D LUT) of `size`³ entries (2..256): input device RGB (0..1), output
/// XYZ / white Y, red index fastest.
std::string export_cube(const Profile& profile, int size = 33, double rgb_scale = 0);

/// Per-patch CSV: id, RGB, reference XYZ, estimate XYZ, ΔE76, ΔE94, ΔE00, ΔL, ΔC, ΔH, ΔE_xyz,
/// rel_Y (and the leave-one-out estimate and ΔE00 when loo_XYZ has rows).
std::string patch_csv(const std::vector<std::string>& ids, const PatchMatrix& camera_RGB,
                      const PatchMatrix& reference_XYZ, const PatchMatrix& estimated_XYZ,
                      const Vec3& white, const PatchMatrix& loo_XYZ = PatchMatrix());

/// Uncompressed little-endian baseline TIFF, 3 × 32-bit IEEE float samples per pixel
/// (SampleFormat 3, PlanarConfiguration 1, one strip), interleaved input of width × height × 3.
std::vector<uint8_t> float_tiff(const float* pixels, int width, int height,
                                const std::string& description = "CIE XYZ");
/// The same with `bands` 32-bit float samples per pixel (band fastest), Photometric
/// MinIsBlack with bands − 1 ExtraSamples: spectral images (linearisation/spectral.hpp).
std::vector<uint8_t> float_tiff_bands(const float* pixels, int width, int height, int bands,
                                      const std::string& description);
/// An interleaved 3-channel float image (RGB in, XYZ out), row 0 at the top.
struct Image3f {
  int width = 0, height = 0;
  std::vector<float> pixels;  ///< width × height × 3
};

/// Reads a colour PFM ("PF", either endianness); Error(ParseError) naming the problem.
Image3f read_pfm(const std::string& bytes);

/// Applies a profile's model to a linear camera-RGB image (same units as the training RGB).
Image3f apply_profile(const Profile& profile, const float* rgb, int width, int height);

/// Portable float map (PF, little-endian scale -1, bottom row first as the format requires).
std::vector<uint8_t> float_pfm(const float* pixels, int width, int height);

}  // namespace tristim

// Exports of a profile for other tools: ICC v4 input profile (lcms2), .cube 3D LUT, per-patch
// CSV; and 32-bit float image files (TIFF, PFM) for XYZ images.
//
// Device encoding of the ICC and .cube exports: device value d = camera RGB / rgb_scale
// (default: the profile's training rgb_max), so d = 1 is the brightest training value.
// Output: XYZ relative to the profile's white (white Y -> 1). The ICC PCS is D50: when the
// profile white is not D50, XYZ is adapted with Bradford; a v4 profile records it in 'chad' and
// has wtpt = D50, a v2 profile (no 'chad' in v2) has wtpt = the profile white (see export.cpp).
// The ICC header's date is fixed, so one profile always gives the same bytes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim {

struct IccOptions {
  double rgb_scale = 0;       ///< 0: profile.rgb_max
  /// CLUT grid of LUT-based profiles (2..255). 49: on the Passport degree-2 profile a 33-point
  /// grid read back by lcms2 at mean ΔE00 0.050, max 0.27 (darkest patch); 49 well inside the
  /// goals (mean < 0.05, max < 0.3; tests/core/profile/export_readers_test.cpp). ~0.7 MB.
  int grid_points = 49;
  double shaper_gamma = 2.2;  ///< A-curve of LUT profiles: grid is uniform in d^(1/gamma)
  std::string description;    ///< empty: "tristim <model> (<objective>)"
  /// ICC version: 4.3 (default) or 2.4 (for readers without v4 support, e.g. Argyll 2.3's
  /// icclib, which refuses every v4 profile). v2: AToB0 is a lut16Type ('mft2': 4096-entry input
  /// tables, the same 16-bit XYZ encoding as v4), wtpt is the profile white, no 'chad', no ID.
  double version = 4.3;
};

/// ICC v4.3 input-class RGB -> PCS XYZ profile. A plain 3×3 model gives a matrix/shaper
/// profile (rXYZ/gXYZ/bXYZ + identity TRCs); every other model an AToB0 lutAtoBType with
/// A curves (gamma 1/shaper_gamma), a 16-bit CLUT sampled from the model holding XYZ offset and
/// scaled to keep -0.5..2 (negative predictions survive at the nodes), and B curves that map it
/// to PCSXYZ, clipping to 0 .. 1 + 32767/32768 only there.
/// Error(ExportFailed) if lcms2 refuses.
std::vector<uint8_t> export_icc(const Profile& profile, const IccOptions& options = {});

/// Runs an ICC profile (bytes) through lcms2: device RGB (0..1, N × 3) -> PCS XYZ (D50, Y=1),
/// relative colorimetric. For checks and tests.
PatchMatrix icc_device_to_XYZ(const std::vector<uint8_t>& icc, const PatchMatrix& device_RGB);

/// The .cube's 1D shaper: rows and exponent (u = d^(1/kCubeShaperGamma)).
constexpr int kCubeShaperSize = 4096;
constexpr double kCubeShaperGamma = 2.2;

/// .cube in the Resolve convention (read by Resolve and OpenColorIO): a 1D shaper of
/// kCubeShaperSize rows, u = d^(1/2.2) per channel, followed by a 3D LUT of `size`³ rows (2..129,
/// red fastest) holding XYZ / white Y at u. Input d = camera RGB / rgb_scale (0..1, clamped).
/// The shaper puts grid points where the model bends (near black, where the roots of a
/// root-polynomial are steep): on the Passport degree-2 profile a 33³ linear-domain grid was off by
/// up to 5.5 ΔE00 in the shadows, the shaped one by < 0.3 (tests/core/profile/export_readers_test).
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

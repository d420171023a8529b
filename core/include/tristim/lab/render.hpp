// tristim — the colorimetry lab's chart photographs: a colour chart's measured reflectances seen
// by a camera's measured spectral sensitivities under an illuminant (the virtual camera,
// simulate/virtual_camera.hpp), drawn head-on or at given corners into a Bayer sensor raster and
// written as a real DNG (lab/dng_writer.hpp) that LibRaw, dcraw_emu and the normal journey open.
//
// Per measurement pixel (one 2×2 CFA block; coordinates as chart/layout.hpp: the image spans
// [0, width] × [0, height]) and channel c, in DN above the black level:
//   u_c  = e · s · ρ_c                       ρ_c: virtual-camera response of the surface under the
//                                            pixel (patch, chart board ρ = 0.03, background ρ = 0.2),
//                                            white diffuser's G = 1; s = saturation (DN);
//                                            e = exposure (white's G as a fraction of s)
//   v_c  = u_c · f(r) + φ · e · s · w_c      fall-off f(r) = 1 − a·r² (r = 1 at the image corners:
//                                            the quadratic term of Guarnera et al. 2018 eq 7);
//                                            veiling flare φ, w = the white diffuser's response
//   DN   = clip(round(v_c + n), 0, s),  n ~ N(0, g·v_c + σ_r²)   shot (gain g) and read noise σ_r
// Edges are 3×3 supersampled; every sensor pixel of a block gets its own noise draw.
// The surface option (surface/surface.hpp) turns the instrument's reflectances into what the
// camera sees in the capture geometry (Abed et al. 2013): the camera sees R', the reference is R.
//
// The truth: per patch the camera RGB `rgb` that sampling the central part of the patch recovers
// exactly when noise and fall-off are off (round(u + φ·e·s·w), clipped), the unquantised value,
// and the reference XYZ of the instrument's reflectance (CIE 1931, Y_white = 100).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/json.hpp"
#include "tristim/lab/dng_writer.hpp"
#include "tristim/methods.hpp"

namespace tristim {

struct LabRenderOptions {
  std::string camera = "Canon_EOS_5D_Mark_II";  ///< one of the 52 (camera_names()), or a label
                                                ///< for `sensitivities`
  SpectralData sensitivities;       ///< R, G, B curves to use instead of the built-in camera (empty: built-in)
  /// "cc24", "passport" or "sg140"; "munsell:<chip>,<chip>,…" (lab_munsell_selection) drawn as a
  /// generated grid; with `reflectances` given, only a label (e.g. the file's name).
  std::string chart = "cc24";
  /// A chart of one's own: reflectances (fractions, one column per patch, names = patch ids) drawn
  /// as a generated grid of lab_grid_shape(N) patches (the layout `custom`, gap 0: `tristim sample
  /// --chart custom --rows R --columns C --corners …` samples it; cells past the N-th show the
  /// board). Empty: the chart `chart`.
  SpectralData reflectances;
  std::string illuminant = "D65";   ///< id (illuminant_spd) or a label for `illuminant_spd`
  SpectralData illuminant_spd;      ///< the SPD to use (empty: illuminant_spd(illuminant))
  MethodChoice surface{"none", {}, {}};  ///< surface correction applied to the reflectances
  int width = 900, height = 600;    ///< measurement image; the sensor has 2·width × 2·height pixels
  std::array<double, 8> corners{};  ///< patch grid corners, A1's first, clockwise; all 0: centred
  double exposure = 0.5;            ///< e: the white diffuser's G as a fraction of saturation, (0, 4]
  double falloff = 0;               ///< a: light lost at the image corners, [0, 0.9]
  double flare = 0;                 ///< φ: veiling flare as a fraction of the white, [0, 1]
  double shot_gain = 0;             ///< g: shot-noise variance per DN (0: no shot noise)
  double read_noise = 0;            ///< σ_r: read noise, DN
  std::uint64_t seed = 1;           ///< noise seed (the same file in every build)
  int bits = 14;                    ///< sensor bit depth, 10..16
  int black = 512;                  ///< black level, DN
  std::string cfa = "RGGB";         ///< 2×2 pattern
  /// The encoding of an RGB image (lab_render_tiff; a DNG is always linear): "linear",
  /// "gamma=<γ>" (stored = x^(1/γ)) or "sRGB" (IEC 61966-2-1), x = DN / saturation in [0, 1].
  std::string oecf = "linear";
  int jpeg_quality = 95;            ///< lab_render_jpeg: libjpeg quality 1..100 (4:4:4, no chroma subsampling)
};

struct LabPatchTruth {
  std::string id;
  std::string cell;                 ///< a generated grid's cell id (R1C1…, the custom layout's); else empty
  std::array<double, 3> rgb{};      ///< DN above black as sampling recovers it (see header)
  std::array<double, 3> linear{};   ///< the same before rounding and clipping
  std::array<double, 3> XYZ{};      ///< reference: instrument reflectance, CIE 1931 2°, Y_white = 100
  bool board = false;               ///< a generated grid's cell past the last reflectance: the board (flat ρ = 0.03)
};

struct LabRender {
  LabRenderOptions options;         ///< as given, corners filled in
  int width = 0, height = 0;        ///< measurement image
  std::vector<std::uint16_t> sensor;  ///< 2·width × 2·height CFA values including the black level
  std::array<double, 8> corners{};
  std::string layout;               ///< the layout drawn: the chart id, or "custom" for a generated grid
  int rows = 0, columns = 0;        ///< its grid
  double saturation = 0;            ///< s: clip level above black, DN
  std::array<double, 3> white{};    ///< DN of the white diffuser (e·s·w)
  std::vector<LabPatchTruth> patches;  ///< in the layout's order
  DngWriteOptions dng;              ///< the DNG's tags (colour matrix fitted on the chart under D65)
  std::vector<double> scene;        ///< width × height × 3: u per pixel (before fall-off, flare, noise)
};

/// Renders the chart. Errors: UnknownId (camera, chart, illuminant, surface method, Munsell chip),
/// InvalidArgument naming the option out of range (a generated grid: 3..2000 patches, unique ids),
/// CornersOutside / CornersCrossed for corners.
LabRender render_lab_chart(const LabRenderOptions& options);

/// The rendering as a DNG file (bytes).
std::vector<std::uint8_t> lab_render_dng(const LabRender& render);

/// The rendering as an RGB image, one pixel per measurement pixel (no CFA), through the OECF
/// (options.oecf) and quantised to 16 bits: a baseline TIFF. Fall-off, flare and noise as in the
/// DNG (one noise draw per pixel and channel).
std::vector<std::uint8_t> lab_render_tiff(const LabRender& render);

/// The same RGB image through the OECF in 8 bits (round(255 · encoded)), written as a baseline JPEG
/// at options.jpeg_quality without chroma subsampling (lab/jpeg_writer.hpp). The truth's `stored`
/// (lab_render_json with full_scale 255) is the 8-bit value before compression; sampling the
/// decoded JPEG gives it back within the compression's error (tests: 1.5 DN on a patch's mean at 95).
std::vector<std::uint8_t> lab_render_jpeg(const LabRender& render);

/// Encoded value of a DN through options.oecf, in [0, 1]. Error(InvalidArgument) for an unknown OECF.
double lab_encode(const LabRenderOptions& options, double dn, double saturation);

/// The truth as JSON: camera, chart, illuminant, sizes, corners, saturation, white, and per patch
/// {id, rgb, linear, XYZ}; a generated grid adds "layout" {chart "custom", rows, columns},
/// "sample_args" (the `tristim sample` options that sample it) and per patch "cell" (every cell of the
/// grid: an empty one as a patch of the board, id = its cell, "board": true); with `full_scale` > 0 (an image through the OECF) also the OECF and
/// per patch `stored`: round(full_scale · encode(rgb)), what sampling the image recovers (noise off).
json::Value lab_render_json(const LabRender& render, double full_scale = 0);

/// The rendered patches' reference as a patch CSV (read_patch_csv reads it back): the header
/// "id,X,Y,Z", then per patch of the truth its id — a generated grid's cell (R1C1…, the board's
/// cells included, as the custom layout samples them) — and the XYZ (17 significant digits).
std::string lab_reference_csv(const LabRender& render);

/// What `tristim lab render` writes and prints, and what the page's Lab mode receives: the DNG's
/// bytes and the truth as JSON text (lab_render_json, pretty-printed).
struct LabRenderFiles {
  std::vector<std::uint8_t> dng;    ///< the file's bytes (DNG, TIFF or JPEG)
  std::string truth;
  std::string reference;            ///< lab_reference_csv: the reference the journey fits against
};
/// format: "dng" (or empty; options.oecf must be "linear"), "tiff" or "jpeg" (the truth adds
/// "jpeg_quality").
LabRenderFiles lab_render_files(const LabRenderOptions& options, const std::string& format = "dng");

/// lab_render_files with `reflectances` as the chart of one's own (LabRenderOptions::reflectances;
/// the page's upload, read by read_reflectance_file); `options.chart` is its label.
LabRenderFiles lab_render_reflectance_files(LabRenderOptions options, const SpectralData& reflectances,
                                            const std::string& format = "dng");

/// OECFs offered for TIFF and JPEG output (lab_encode accepts any gamma=<0.2..5>): "linear",
/// "sRGB", "gamma=1.8", "gamma=2.2".
std::vector<std::string> lab_oecf_ids();

/// Chart ids lab rendering draws ("cc24", "passport", "sg140"); besides them "munsell:…" and
/// LabRenderOptions::reflectances.
std::vector<std::string> lab_chart_ids();

/// Rows and columns of the generated grid for n patches: columns = ⌈√(1.5 n)⌉ (a 3:2 chart, as the
/// ColorChecker's 6×4), rows = ⌈n / columns⌉. InvalidArgument for n < 1.
std::array<int, 2> lab_grid_shape(int n);

/// Munsell matte chips (munsell_reflectances(), ids as munsell_ids()) chosen by `selection`: a
/// comma-separated list of chip ids ("5R4/14,10YR6/10") or hue pages ("5R": every chip of that hue,
/// by value then chroma), optionally after "munsell:". Columns in the order given, no repeats.
/// Error(UnknownId) naming a token that is neither a chip nor a hue page.
SpectralData lab_munsell_selection(const std::string& selection);

}  // namespace tristim

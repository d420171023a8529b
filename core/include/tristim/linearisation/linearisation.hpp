// Linearisation: the camera's inverse OECF per channel, from stored values (RAW, or non-linear
// TIFF/PNG/JPEG) to values proportional to exposure. One table row per method; the recipe's
// `linearisation` stage names a row by id and gives its options (a MethodChoice), which with the
// data fully decide the fit.
//
// Rows (ids are the same in C++, JS, files and the UI):
//   identity              RAW data are linear already
//   gamma                 x^γ, γ stated (OpenCV ccm's default 2.2)
//   sRGB                  IEC 61966-2-1 decoding
//   grey-polynomial       per channel, degree K, on the grey patches (ISO 14524 style; OpenCV's
//   grey-log-polynomial   GRAYPOLYFIT / GRAYLOGPOLYFIT family, but one curve per channel)
//   colour-polynomial     per channel, degree K, against the reference's linear sRGB on every
//   colour-log-polynomial patch (OpenCV's COLORPOLYFIT / COLORLOGPOLYFIT)
//   Guarnera2018          power law (Guarnera et al. 2018 eq 8; core/src/linearisation/guarnera2018.cpp)
//   Shen2008              non-grey samples with known reflectances (Shen, Xin, Yang & Lou 2008,
//                         eqs 6-22; see oecf_Shen2008.hpp)
//
// Units: every curve reads x = stored value / full_scale (so x = 1 is the encoding's full scale:
// 255 for 8-bit, 65535 for 16-bit) and returns a linear value:
//   identity              the stored value unchanged (DN)
//   gamma, sRGB           0..1 (full scale -> 1)
//   grey-*                the greys' reflectance factor (a grey of mean reflectance 0.2 -> 0.2)
//   colour-*              linear sRGB of the reference, its white -> 1
//   Shen2008              relative: 1 at the brightest fitted patch of that channel (the paper's
//                         "normalized linear response"; the scale c0 is not recoverable, eq 20)
// A characterisation model absorbs per-channel scales, so these units never change a fit's
// colour error except through the offsets and shapes of the curves.
//
// Shapes: PatchMatrix N × 3 (R, G, B), one row per patch.
#pragma once
#include <array>
#include <limits>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"
#include "tristim/methods.hpp"

namespace tristim {

/// What a method may fit from. Everything but camera_RGB is optional (empty when absent).
struct LinearisationData {
  std::vector<std::string> ids;   ///< patch ids, one per row (normalised, see normalise_patch_id)
  PatchMatrix camera_RGB;         ///< stored (non-linear) values, N × 3
  PatchMatrix reference_XYZ;      ///< known XYZ of the patches (0 rows when absent)
  Vec3 white = whites::D50();     ///< XYZ of the perfect diffuser, same scale as reference_XYZ
  SpectralData reflectances;      ///< known reflectances (fractions), columns named like `ids` (empty when absent)
  SpectralData basis_reflectances;  ///< Shen2008 with basis=user: the set the PCA basis is built from
  double full_scale = 0;          ///< the largest value the encoding can hold (255, 65535); 0: max of the data
};

/// A patch whose stored value in one channel lies outside the range that channel's curve was
/// fitted on, so the curve is extrapolated there (Shen2008 fits on the non-grey patches and is
/// applied to all: a chart's white and light greys lie above every chromatic patch).
struct Extrapolation {
  std::string patch;   ///< patch id
  int channel = 0;     ///< 0, 1, 2 (R, G, B)
  double x = 0;        ///< stored value / full scale
  double bound = 0;    ///< the end of the fitted range it passes (domain[channel][0] or [1])
  double relative = 0; ///< (x − bound) / bound: > 0 above the range, < 0 below it (a bound of 0: / the range's width)
};

/// A fitted linearisation: enough to apply it and to show how it was made.
struct Linearisation {
  MethodChoice choice;            ///< method id and its (completed) options
  /// Per channel, meaning depends on the method: polynomial rows c_0..c_K (ascending powers of
  /// x, or of ln x for the log rows); gamma {γ}; identity and sRGB: empty.
  std::array<std::vector<double>, 3> coefficients;
  double full_scale = 1;          ///< stored value that x = 1 stands for
  /// Range of x each channel's curve was fitted on ([0, 1] for curves not fitted to data).
  std::array<std::array<double, 2>, 3> domain{{{0, 1}, {0, 1}, {0, 1}}};
  /// Per channel: grey-/colour-*: coefficient of determination of the fit; Shen2008 when greys
  /// exist: the paper's R² (Tables I-II), the squared correlation between the recovered curve
  /// and the grey-based polynomial of the same order, sampled over the greys' range; NaN when
  /// there is nothing to compare with.
  Vec3 r_squared = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  std::vector<std::string> fitted;   ///< ids of the patches the curves were fitted on (any channel)
  std::vector<std::string> greys;    ///< grey patches (fitted on by grey-*, compared with by Shen2008)
  std::string grey_reason;           ///< how the greys were chosen ("given", or the automatic rule with each ΔE00)
  /// Shen2008: the grey-based polynomial of the same order K per channel (Fig 5), in the grey
  /// methods' units; empty when there are no greys.
  std::array<std::vector<double>, 3> grey_coefficients;
  bool monotonic = true;          ///< false: a curve is not increasing over its fitted range (see message)
  /// Shen2008: every patch and channel outside the fitted range (a warning in message too);
  /// empty for the other rows.
  std::vector<Extrapolation> extrapolated;
  std::string message;            ///< warnings ("; "-separated), empty when none
};

/// One row of the linearisation table.
struct LinearisationMethod {
  MethodInfo info;
  /// What the fit needs besides camera RGB: "" (nothing), "greys" (reference XYZ or
  /// reflectances to find or check greys), "reference" (reference XYZ), "reflectances".
  std::string needs;
  /// Fits from data with the (completed) options.
  Linearisation (*fit)(const LinearisationData& data, const MethodChoice& choice);
  /// Stored value of one channel (0, 1, 2) -> linear value.
  double (*apply)(const Linearisation& fitted, int channel, double value);
  /// Linear value -> stored value (the inverse of apply over the fitted range; numerical for
  /// polynomials, ends clamped to [0, full_scale] where the curve cannot be inverted).
  double (*inverse)(const Linearisation& fitted, int channel, double linear);
};

/// Every linearisation method, in a stable order (`identity` first).
const std::vector<LinearisationMethod>& linearisation_table();
/// A row by id; Error(UnknownId) naming the id otherwise.
const LinearisationMethod& linearisation_method(const std::string& id);
/// What a row's `needs` asks of the data, as one phrase for pickers ("fitted against the reference
/// XYZ of every patch"); Error(UnknownId) for a value no row has.
std::string linearisation_needs_text(const std::string& needs);
/// A row as the page's picker lists it: the MethodInfo's fields, `needs` and its phrase.
struct LinearisationListing {
  std::string id, label, reference, needs, needs_text;
  std::vector<OptionSpec> options;
};
/// linearisation_table() as listings, in its order.
std::vector<LinearisationListing> linearisation_listing();
/// Fits the chosen method (options checked and completed from the table).
/// Errors: UnknownId, InvalidArgument (options), TooFewPatches, PatchMismatch (ids and rows
/// differ), MissingColumn (a needed reference or reflectance is absent), NonFinite,
/// WavelengthMismatch, NoUsableData (every sample clipped), IllConditioned.
Linearisation fit_linearisation(const MethodChoice& choice, const LinearisationData& data);
/// Applies a fitted linearisation to every row.
PatchMatrix linearise(const Linearisation& fitted, const PatchMatrix& camera_RGB);
/// The inverse: linear values -> stored values.
PatchMatrix delinearise(const Linearisation& fitted, const PatchMatrix& linear_RGB);
/// Applies a fitted linearisation to an interleaved RGB image in place (n_pixels × 3 floats).
void linearise_image(const Linearisation& fitted, float* rgb, size_t n_pixels);
/// linearise_image for an image taken in pieces (a strip or block at a time): the per-channel
/// tables of whole-number samples (3 × 256 KB) are filled once and kept between calls, not made
/// afresh for every piece. The same floats as linearise_image. `fitted` must outlive it.
class ImageLineariser {
 public:
  explicit ImageLineariser(const Linearisation& fitted);
  void apply(float* rgb, size_t n_pixels);

 private:
  const Linearisation& fitted_;
  const LinearisationMethod& method_;
  std::vector<std::uint32_t> tables_;  // 3 × 65536 floats' bits, made on first use
};

/// The curve of one channel sampled at `n` stored values evenly spaced over its fitted range
/// (domain), for plots: x (stored / full_scale), the curve and, for Shen2008 with greys, the
/// grey-based curve; both Shen curves scaled to 1 at the top of the range (the paper's Fig 5).
struct CurveSamples {
  std::vector<double> x, linear, grey_based;
};
CurveSamples sample_curve(const Linearisation& fitted, int channel, int n = 101);

/// JSON of a fitted linearisation, written by its field list (below; every double with 17
/// significant digits: exact round trip): {"method", "parameters", "settings", "full_scale",
/// "coefficients": [[..],[..],[..]], "domain", "r_squared", "fitted", "greys", "grey_reason",
/// "grey_coefficients", "monotonic", "message"} and, when not empty, "extrapolated": [{"patch",
/// "channel", "x", "bound", "relative"}]. NaN R² is written as null.
json::Value linearisation_json(const Linearisation& fitted);
/// Reads it back by the same list (Error(ProfileInvalid) naming the member, an unknown one too;
/// UnknownId for an unknown method).
Linearisation linearisation_from_json(const json::Value& value);

// --- building blocks shared by the rows (exposed for tests) --------------------------------

/// The greys of a patch set and why. `given`: ids (empty: automatic). Automatic rule (OpenCV
/// ccm's Color::getGray): CIEDE2000 between a patch's L*a*b* (relative to data.white) and the
/// neutral of the same L*, (L*, 0, 0), below `threshold` (OpenCV's JDN, 2). The reference comes
/// from data.reference_XYZ or, without it, from data.reflectances under D65 (2°).
struct GreySelection {
  std::vector<int> rows;   ///< indices into data.ids
  std::string reason;      ///< e.g. "automatic: ΔE00 from neutral < 2 (D1 0.41, D2 0.35, …)"
};
GreySelection select_greys(const LinearisationData& data, const std::vector<std::string>& given, double threshold);

/// The grey options of a fit that leaves the grey patches out by default (the Shen2008 row and
/// the spectral characterisation, spectral.hpp): grey (';'-separated ids, empty: automatic),
/// grey_threshold (ΔE00 of the automatic rule), use_greys (0/1). One list, so both read alike.
std::vector<OptionSpec> grey_options();
/// The rows of `data` a fit with those options trains on: every row when use_greys = 1, else the
/// rows select_greys does not pick (by the choice's grey and grey_threshold). `greys` receives
/// the selection.
std::vector<int> training_rows(const LinearisationData& data, const MethodChoice& choice, GreySelection& greys);

/// Splits an id list "A1;A2,A3" (';' or ',' separated; the recipe syntax uses ';').
std::vector<std::string> split_ids(const std::string& list);

/// Least-squares polynomial c_0..c_degree (ascending) of y on x; Error(TooFewPatches) with fewer
/// than degree + 1 points, Error(IllConditioned) if the x are not distinct enough.
std::vector<double> polyfit(const std::vector<double>& x, const std::vector<double>& y, int degree);
/// Σ c_k x^k (Horner).
double polyval(const std::vector<double>& c, double x);
/// Coefficient of determination 1 − SS_res / SS_tot of predictions `fit` for `y`.
double coefficient_of_determination(const std::vector<double>& y, const std::vector<double>& fit);
/// Squared Pearson correlation of two equally long sequences (NaN if either is constant).
double squared_correlation(const std::vector<double>& a, const std::vector<double>& b);

/// IEC 61966-2-1 sRGB decoding (encoded 0..1 -> linear), odd-symmetric for negative inputs; the
/// encoder is colorimetry.hpp's sRGB_encode.
double sRGB_decode(double encoded);

}  // namespace tristim

// Their field lists (defined in linearisation.cpp): the JSON, the CLI's output and the wasm
// binding use them. A Linearisation is its choice's method, parameters and settings at the top
// level, then its members; CurveSamples writes grey_based only when there is one.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(Extrapolation);
TRISTIM_FIELDS_DECLARE(Linearisation);
TRISTIM_FIELDS_DECLARE(CurveSamples);
/// A Linearisation reads by its list and is then checked, wherever it is read (a profile, a
/// spectral model, a JS object): a known method with its options completed from the table
/// (UnknownId / InvalidArgument), full_scale > 0 and coefficients for every curve that needs them
/// (the context's code).
template <>
struct Checks<Linearisation> {
  static void check(Linearisation& l, const Context& c, const std::string& p);
};
}  // namespace tristim::fields

// tristim — error type shared by every module (native and wasm alike).
#pragma once
#include <stdexcept>
#include <string>

namespace tristim {

/// Machine-readable error codes. The string form (error_code_name) is what JS sees as `.code`
/// and what tests assert on; keep names stable once released.
enum class ErrorCode {
  InvalidArgument,    ///< a parameter out of range or of the wrong kind
  UnknownId,          ///< an unknown chart, illuminant, observer, camera, model or method id
  // --- files and parsing
  EmptyFile,          ///< zero bytes or no data rows
  ParseError,         ///< structurally malformed file (bad header, unterminated block …)
  MissingColumn,      ///< a required column is absent
  NonNumeric,         ///< a cell that must be a number is not
  NonFinite,          ///< NaN or ±Inf in a numeric cell
  NonMonotonic,       ///< wavelengths not strictly increasing
  DuplicateId,        ///< two rows with the same patch id
  RowLength,          ///< a row with the wrong number of values
  // --- RAW decoding and frames
  RawUnsupported,     ///< not a RAW LibRaw can decode (JPEG, PNG, random bytes …)
  RawTruncated,       ///< file ends before the image data does
  RawCorrupt,         ///< header or data inconsistent (absurd dimensions …)
  RawTooLarge,        ///< would exceed the memory budget
  FrameMismatch,      ///< dark/flat frame of another size or camera
  FlatFieldZero,      ///< a flat field with zero / non-positive pixels
  // --- chart geometry and sampling
  CornersOutside,     ///< a chart corner outside the image
  CornersCrossed,     ///< self-intersecting or degenerate quadrilateral
  PatchTooSmall,      ///< sampling area under the minimum pixel count
  // --- fitting
  TooFewPatches,      ///< fewer patches than model terms
  IllConditioned,     ///< singular / collinear design matrix
  PatchMismatch,      ///< RGB and reference tables do not pair up
  NegativeValue,      ///< negative value where physics forbids it (e.g. XYZ)
  FitFailed,          ///< the optimiser could not produce a result
  // --- profiles and exports
  ProfileVersion,     ///< a profile of an unknown/unsupported version
  ProfileInvalid,     ///< a profile with missing or inconsistent fields
  ExportFailed,       ///< a writer (ICC, TIFF …) failed
  SameIlluminant,     ///< a dual-illuminant camera profile (DCP) whose two calibration illuminants are equal
  // --- recipes (profile/recipe.hpp)
  RecipeVersion,      ///< a recipe of an unknown/unsupported version
  RecipeInvalid,      ///< a recipe with an unknown field, a missing field or a wrong type
  // --- methods of the papers and what they read
  ImageUnsupported,   ///< not an image any decoder here reads (TIFF/PNG/JPEG), or an unsupported variant
  ImageCorrupt,       ///< an image file that is truncated or inconsistent
  WavelengthMismatch, ///< spectral sets on incompatible wavelength ranges
  IllPosed,           ///< a request with no unique answer (e.g. every Saunderson coefficient free)
  MissingMetadata,    ///< a RAW without the exposure time / f-number a method needs
  NoUsableData,       ///< every sample saturated or dark, nothing left to fit
  ChartNotFound,      ///< automatic chart detection found no chart
  LimitExceeded,      ///< an input beyond a stated resource limit (size, count, depth)
  Internal,           ///< a bug: an invariant broke
};

/// Stable upper-snake name of a code, e.g. ErrorCode::MissingColumn -> "MISSING_COLUMN".
const char* error_code_name(ErrorCode code);

/// The one exception type for bad input. `what()` names the input and, for files, the line.
class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ErrorCode code() const noexcept { return code_; }
  const char* code_name() const noexcept { return error_code_name(code_); }

 private:
  ErrorCode code_;
};

}  // namespace tristim

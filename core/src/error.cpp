#include "tristim/error.hpp"

namespace tristim {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidArgument: return "INVALID_ARGUMENT";
    case ErrorCode::UnknownId: return "UNKNOWN_ID";
    case ErrorCode::EmptyFile: return "EMPTY_FILE";
    case ErrorCode::ParseError: return "PARSE_ERROR";
    case ErrorCode::MissingColumn: return "MISSING_COLUMN";
    case ErrorCode::NonNumeric: return "NON_NUMERIC";
    case ErrorCode::NonFinite: return "NON_FINITE";
    case ErrorCode::NonMonotonic: return "NON_MONOTONIC";
    case ErrorCode::DuplicateId: return "DUPLICATE_ID";
    case ErrorCode::RowLength: return "ROW_LENGTH";
    case ErrorCode::RawUnsupported: return "RAW_UNSUPPORTED";
    case ErrorCode::RawTruncated: return "RAW_TRUNCATED";
    case ErrorCode::RawCorrupt: return "RAW_CORRUPT";
    case ErrorCode::RawTooLarge: return "RAW_TOO_LARGE";
    case ErrorCode::FrameMismatch: return "FRAME_MISMATCH";
    case ErrorCode::FlatFieldZero: return "FLAT_FIELD_ZERO";
    case ErrorCode::CornersOutside: return "CORNERS_OUTSIDE";
    case ErrorCode::CornersCrossed: return "CORNERS_CROSSED";
    case ErrorCode::PatchTooSmall: return "PATCH_TOO_SMALL";
    case ErrorCode::TooFewPatches: return "TOO_FEW_PATCHES";
    case ErrorCode::IllConditioned: return "ILL_CONDITIONED";
    case ErrorCode::PatchMismatch: return "PATCH_MISMATCH";
    case ErrorCode::NegativeValue: return "NEGATIVE_VALUE";
    case ErrorCode::FitFailed: return "FIT_FAILED";
    case ErrorCode::ProfileVersion: return "PROFILE_VERSION";
    case ErrorCode::ProfileInvalid: return "PROFILE_INVALID";
    case ErrorCode::ExportFailed: return "EXPORT_FAILED";
    case ErrorCode::SameIlluminant: return "SAME_ILLUMINANT";
    case ErrorCode::RecipeVersion: return "RECIPE_VERSION";
    case ErrorCode::RecipeInvalid: return "RECIPE_INVALID";
    case ErrorCode::ImageUnsupported: return "IMAGE_UNSUPPORTED";
    case ErrorCode::ImageCorrupt: return "IMAGE_CORRUPT";
    case ErrorCode::WavelengthMismatch: return "WAVELENGTH_MISMATCH";
    case ErrorCode::IllPosed: return "ILL_POSED";
    case ErrorCode::MissingMetadata: return "MISSING_METADATA";
    case ErrorCode::NoUsableData: return "NO_USABLE_DATA";
    case ErrorCode::ChartNotFound: return "CHART_NOT_FOUND";
    case ErrorCode::LimitExceeded: return "LIMIT_EXCEEDED";
    case ErrorCode::Internal: return "INTERNAL";
  }
  return "INTERNAL";
}

}  // namespace tristim

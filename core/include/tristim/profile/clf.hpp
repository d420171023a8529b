// Academy/ASC Common LUT Format (CLF 3.0, S-2014-006 "Common LUT Format (CLF) – A Common File
// Format for Look-Up Tables", version 3) for an ACES Input Transform: a `ProcessList` with an
// `Info` element carrying the recipe, a `LUT1D` where a linearisation applies, then the `Matrix`
// (camera-native linear RGB -> ACES2065-1, 32-bit float in and out). OpenColorIO reads it
// (`ociochecklut`), as do Resolve, Nuke and the ACES reference tools.
// Also the plain 3×3 text and the IDT's JSON, so the CLI and the page write the same bytes.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/io/json.hpp"
#include "tristim/profile/idt.hpp"

namespace tristim {

/// What a CLF holds (what write_clf writes and read_clf reads back).
struct ClfDocument {
  std::string id;                  ///< ProcessList id
  std::string name;                ///< ProcessList name
  std::string description;         ///< ProcessList Description
  std::string input_descriptor, output_descriptor;
  std::vector<std::pair<std::string, std::string>> info;  ///< Info children: element name, text
  /// LUT1D values, one RGB triple per entry on an even grid of inputs 0..1 (empty: no LUT1D).
  std::vector<Vec3> lut1d;
  Mat3 matrix = Mat3::Identity();
};

/// The XML (UTF-8, LF). Error(InvalidArgument) for an Info name that is no XML name, a non-finite
/// value or a LUT1D of 1 or more than 65536 entries.
std::string write_clf(const ClfDocument& clf);

/// Strict reader of what write_clf writes (any whitespace, attributes in any order, comments):
/// ProcessList, optional Description / InputDescriptor / OutputDescriptor / Info, an optional
/// LUT1D and one Matrix with dim="3 3". Error(ParseError) naming the offset for broken XML or
/// another structure, NonNumeric / NonFinite for a bad array value, RowLength for an array of the
/// wrong size, LimitExceeded beyond 65536 LUT entries.
ClfDocument read_clf(std::string_view text);

/// ACES2065-1 of camera RGB through the CLF: LUT1D (linear interpolation, inputs clamped to 0..1
/// as in CLF 3) then the matrix.
Vec3 apply_clf(const ClfDocument& clf, const Vec3& rgb);

/// The recipe of an IDT as it is written in the CLF's Info and the JSON, in order: e.g.
/// {"Camera", "Canon EOS 5D Mark II"}, {"Illuminant", "D55"}, {"Training", "190 (rawtoaces v1)"}.
using IdtRecipe = std::vector<std::pair<std::string, std::string>>;

/// The CLF of an IDT: Info = tristim's version, the method, the recipe, the white balance,
/// exposure and the fit's errors; Matrix = result.camera_matrix().
ClfDocument idt_clf(const IdtResult& result, const IdtRecipe& recipe);
/// The plain 3×3: three lines of three numbers (camera-native RGB -> ACES2065-1), the
/// white balance and B in comment lines starting with '#'.
std::string idt_matrix_text(const IdtResult& result);
/// {"matrix": B (3×3 row major, white-balanced RGB -> ACES2065-1), "white_balance": [R, G, B],
///  "camera_matrix", "exposure", "adaptation", "recipe", "errors": {ΔE76/ΔE00 mean, max, per
///  sample}, "status", "message", "iterations"}.
json::Value idt_json(const IdtResult& result, const IdtRecipe& recipe);
/// A CLF read back as JSON for a summary: descriptors, info, lut1d size, matrix, the ACES of
/// camera (1, 1, 1).
json::Value clf_json(const ClfDocument& clf);

}  // namespace tristim

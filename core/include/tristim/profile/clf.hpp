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
/// The Training entry of the built-in set.
inline constexpr const char* kIdtTraining190 = "190 (rawtoaces v1)";

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
/// What `tristim idt` writes and the page downloads: the CLF, the plain 3×3 and the JSON text
/// (idt_json, 2-space indent).
struct IdtFiles {
  std::string clf, matrix, json;
  IdtResult result;
};
IdtFiles idt_files(const IdtResult& result, const IdtRecipe& recipe);
/// The recipe in the order the CLI and the page write it: the source (e.g. {"Camera", name}), the
/// illuminant (e.g. {"Illuminant", "D55"}), the training set ("" for a chart: none) and the adaptation.
IdtRecipe idt_recipe(const std::pair<std::string, std::string>& source, const std::pair<std::string, std::string>& illuminant,
                     const std::string& training, ChromaticAdaptation adaptation);
/// The IDT of a built-in camera (camera_ssf) under a built-in illuminant (illuminant_spd) with the
/// 190 training spectra: `tristim idt --camera <name> --illuminant <id> [--adaptation a]`.
IdtFiles idt_camera_files(const std::string& camera, const std::string& illuminant, const std::string& adaptation);
/// The IDT of sensitivities given as a CSV (read_ssf_csv: wavelength, R, G, B; `name` names the
/// file in the recipe and in errors) under a built-in illuminant with the 190 training spectra:
/// `tristim idt --sensitivities <name> --illuminant <id> [--adaptation a]`.
IdtFiles idt_sensitivities_files(std::string_view csv, const std::string& name, const std::string& illuminant,
                                 const std::string& adaptation);
/// The IDT of a chart (idt_from_patches) named by its camera-RGB and reference inputs and its
/// illuminant entry ({"Illuminant", id} or {"IlluminantFile", name}):
/// `tristim idt --rgb <rgb_name> --reference <reference_name> --illuminant <id>`.
IdtFiles idt_chart_files(const std::vector<Vec3>& camera_RGB, const std::vector<Vec3>& reference_XYZ,
                         const Vec3& illuminant_white_XYZ, const std::string& adaptation, const std::string& rgb_name,
                         const std::string& reference_name, const std::pair<std::string, std::string>& illuminant);

/// A CLF read back as JSON for a summary: descriptors, info, lut1d size, matrix, the ACES of
/// camera (1, 1, 1).
json::Value clf_json(const ClfDocument& clf);

}  // namespace tristim

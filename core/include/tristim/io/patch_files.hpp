// Readers for measurement files: CSV and CGATS.17 (ArgyllCMS .ti1/.ti2/.ti3/.cie/.cht data blocks,
// i1Profiler exports). Every malformed input throws tristim::Error with a code and a message
// naming the file and the 1-based line:
//   EmptyFile      no bytes, or a header but no data rows
//   ParseError     structure broken (no BEGIN_DATA_FORMAT, unterminated block, bad header)
//   MissingColumn  no usable value columns, or an incomplete triplet (X and Y but no Z …)
//   NonNumeric     a cell that must be a number is not (or is empty)
//   NonFinite      NaN or ±Inf
//   NonMonotonic   wavelengths not strictly increasing
//   DuplicateId    two rows with the same (normalised) patch id
//   RowLength      a row with the wrong number of values
#pragma once
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"

namespace tristim {

/// "A01" -> "A1", "a01" -> "A1", " B 3 " -> "B3", "R01C02" -> "R1C2"; other ids are trimmed and
/// returned unchanged. Letters are upper-cased only in letter+digits ids (chart patch ids).
/// This is the key patches are matched by (a file's "A01" pairs with a chart's "A1"); it is never
/// what an output writes: outputs write the id as the user's file spelled it (PatchTable::labels).
std::string normalise_patch_id(std::string_view id);

/// Cells of a delimited text file: header and rows, with the 1-based line of each row.
/// Delimiter: ',' ';' or tab, whichever the header uses most. '#' starts a comment line; blank
/// lines are skipped; a UTF-8 BOM and CRLF are accepted; "double quoted" cells may hold the
/// delimiter. Every row must have the header's length (Error RowLength).
struct TextTable {
  std::string source;  // file name for messages
  std::vector<std::string> header;
  int header_line = 0;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> lines;  // 1-based line of each row
  /// Index of the first column whose name matches one of `names` case-insensitively, or -1.
  int find(std::initializer_list<const char*> names) const;
};
TextTable parse_delimited(std::string_view text, std::string_view source);

/// Number in a cell (a decimal comma "0,5" is accepted); Error(NonNumeric) / Error(NonFinite)
/// naming source, line and column.
double parse_cell(const std::string& cell, std::string_view source, int line, std::string_view column);

/// Spectral CSV: first column wavelength (nm, strictly increasing), one column per sample.
SpectralData read_spectral_csv(std::string_view text, std::string_view source);
/// An illuminant's relative spectral power distribution from a spectral CSV: the wavelength column
/// and exactly one value column (Error(InvalidArgument) naming the columns when there are more,
/// rather than silently taking the first); values finite, none negative (NegativeValue), not all
/// zero (NoUsableData).
SpectralData read_illuminant_csv(std::string_view text, std::string_view source);
/// Reflectances from any patch file with spectra (spectral CSV, CGATS/.cie with SPEC_ or nm
/// columns; read_patch_file), one column per patch named by its id, as fractions (a table in
/// percent is divided by 100, reflectance_to_fraction). Error(MissingColumn) without spectra.
SpectralData read_reflectance_file(std::string_view text, std::string_view source);

/// A file of per-patch measurements, any of the quantities present.
struct PatchTable {
  std::string format;  // "csv-spectral", "csv", "cgats"
  std::vector<std::string> ids;     // normalised patch ids (normalise_patch_id), unique: the matching keys
  std::vector<std::string> labels;  // the same ids as the file spells them (trimmed), one per id:
                                    // what every output writes back ("Q001" stays "Q001")
  bool has_XYZ = false, has_Lab = false, has_RGB = false, has_spectra = false;
  std::vector<Vec3> XYZ, Lab, RGB;  // one per id when present
  SpectralData spectra;             // names = ids (the keys), when has_spectra (reflectance as in the file)
  std::map<std::string, std::string> keywords;  // CGATS keywords (e.g. ORIGINATOR), unquoted
};

/// The file's own spelling of each of `ids` (normalised ids, e.g. those of a pairing): the label
/// of the table's row with that key, or the id itself when the table has no such row.
std::vector<std::string> patch_labels(const PatchTable& table, const std::vector<std::string>& ids);

/// Per-patch CSV: an id column (patch/id/sample_id/sample_name/sample_loc/name/sample; when there
/// are several, the first whose values are not all plain numbers — i1Profiler's SampleID 1..N next
/// to SAMPLE_NAME A1.., Argyll's SAMPLE_ID next to SAMPLE_LOC; otherwise the index column,
/// otherwise row numbers), an optional index column, and any of X,Y,Z | XYZ_X.. | X_ref.. (the
/// reference columns of the engine's per-patch CSV, patch_csv, which so reads back as a reference);
/// L,a,b | L*,a*,b* | LAB_L.. ; R,G,B | RGB_R.. ; spectral columns named by wavelength
/// ("380", "nm380", "SPECTRAL_380", "SPEC_380", "SPECTRAL_NM380"). Headers are case-insensitive
/// (a lone "b" is Lab b* when L and a are present and RGB blue when R and G are).
PatchTable read_patch_csv(std::string_view text, std::string_view source);

/// CGATS.17 / Argyll: the first data table with a BEGIN_DATA_FORMAT/BEGIN_DATA block. Ids from
/// SAMPLE_ID, SampleID, SAMPLE_NAME or SAMPLE_LOC; columns as for CSV. Spectral values in percent
/// (SPECTRAL_NORM keyword, or any value > 2) are converted to fractions.
PatchTable read_cgats(std::string_view text, std::string_view source);

/// Detects the format from the content (BEGIN_DATA_FORMAT -> CGATS; first header cell a
/// wavelength name such as "wavelength", "nm", "lambda" -> spectral CSV; else per-patch CSV);
/// the extension (.ti1/.ti2/.ti3/.cie/.cht/.cgats/.txt vs .csv) only breaks ties. A spectral CSV
/// comes back as a PatchTable with has_spectra and ids = column names.
PatchTable read_patch_file(std::string_view text, std::string_view file_name);

}  // namespace tristim

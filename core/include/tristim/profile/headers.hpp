// Readers of the headers of the files other tools load — a .cube 3D LUT and an ICC profile — so a
// user can check a file (the engine's export or anyone's) before trusting it. Their results cross
// boundaries by their field lists (io/fields.hpp): the page and the JSON show the same members.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tristim/io/fields.hpp"

namespace tristim {

/// What a .cube file declares (Adobe/Resolve 3D LUT, optionally after a Resolve 1D shaper).
struct CubeHeader {
  std::string title;                          ///< TITLE ("" when absent)
  int size = 0;                               ///< LUT_3D_SIZE (2..256)
  int shaper_size = 0;                        ///< LUT_1D_SIZE (0: no shaper)
  std::int64_t entries = 0;                   ///< rows of the 3D table (size³)
  std::array<double, 3> domain_min{0, 0, 0};  ///< DOMAIN_MIN (or LUT_3D_INPUT_RANGE's lower bound)
  std::array<double, 3> domain_max{1, 1, 1};  ///< DOMAIN_MAX (or LUT_3D_INPUT_RANGE's upper bound)
};

/// Reads a .cube's keywords and counts its rows: every data row three finite numbers, and
/// shaper_size + size³ of them. Other keywords (LUT_1D_INPUT_RANGE, …) are passed over.
/// Error(ParseError) naming `source` and the line: a row without three finite numbers, a size out
/// of range, no LUT_3D_SIZE, a row count other than the sizes say.
CubeHeader read_cube_header(std::string_view text, const std::string& source);

/// What an ICC profile's header and tag table say (ICC.1:2022 §7.2, §7.3), read by lcms2.
struct IccHeader {
  std::int64_t size = 0;           ///< bytes, as the header states (= the file's length)
  std::string version;             ///< "4.4", "2.1", …
  std::string device_class;        ///< "scnr", "mntr", "prtr", …
  std::string colour_space;        ///< data colour space: "RGB", "CMYK", …
  std::string pcs;                 ///< profile connection space: "XYZ" or "Lab"
  std::vector<std::string> tags;   ///< tag signatures in table order
  std::string description;         ///< the 'desc' tag in English ("" when absent)
};

/// Reads an ICC profile's header and tag table. Error(ParseError) naming `source`: shorter than a
/// header, no "acsp" signature at byte 36, a stated size other than the file's, a header or tag
/// table lcms2 refuses.
IccHeader read_icc_header(const std::vector<std::uint8_t>& bytes, const std::string& source);

namespace fields {
TRISTIM_FIELDS_DECLARE(CubeHeader);
TRISTIM_FIELDS_DECLARE(IccHeader);
}  // namespace fields

}  // namespace tristim

// CLI: `tristim inspect <file>` — what a file holds, as JSON: a camera RAW, TIFF, PNG or JPEG
// (capture/image.hpp decode_any: by its bytes, not its name), a DNG camera profile or a CLF
// (cmd_dcp.cpp), a .cube 3D LUT or an ICC profile (profile/headers.hpp: the header the page's
// export step shows when such a file is loaded back).
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/profile/headers.hpp"

namespace tristim::cli {
namespace {

/// A .cube or ICC profile by its extension, as the page picks the reader (web/export/view.js): its
/// header's field list as JSON. Returns false, having printed nothing, for any other name.
bool inspect_header(const std::string& path, std::ostream& out) {
  const std::string ext = ext_of(path);
  if (ext == "cube") {
    out << fields::write(read_cube_header(read_file(path), path)).dump() << "\n";
    return true;
  }
  if (ext == "icc" || ext == "icm") {
    const std::string bytes = read_file(path);
    out << fields::write(read_icc_header(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), path)).dump() << "\n";
    return true;
  }
  return false;
}

int run_inspect(const Args& args, std::ostream& out) {
  args.allow_only({});
  if (args.positional.size() != 1)
    throw Error(ErrorCode::InvalidArgument,
                "inspect takes exactly one RAW, TIFF, PNG or JPEG file (or a DCP, CLF, .cube or ICC profile)");
  const std::string& path = args.positional[0];
  if (inspect_header(path, out)) return 0;
  if (inspect_dcp(path, out)) return 0;  // a DNG camera profile or a CLF (cmd_dcp.cpp)
  const RawImage img = load_raw(path);
  std::string json = metadata_to_json(img.meta);
  json.pop_back();  // add the hash of the linear data to the object
  out << json << ",\"linear_hash\":\"" << hash_hex(linear_data_hash(img)) << "\"}\n";
  return 0;
}

const CommandRegistration inspect_cmd{Command{
    "inspect", "RAW, TIFF, PNG or JPEG metadata; DCP, CLF, .cube or ICC contents (JSON)",
    "usage: tristim inspect <file>\n"
    "The file is a camera RAW (LibRaw), an 8/16-bit TIFF, an 8/16-bit PNG or a JPEG, recognised by\n"
    "its bytes, not its name. Prints one JSON object: format (raw, tiff, png, jpeg), encoding (linear:\n"
    "black-subtracted RAW data; stored: an image's values as stored, no colour management),\n"
    "declared_colour (an image's ICC profile / gAMA / sRGB declarations, reported, not applied), make,\n"
    "model, lens, iso, shutter_s, f_number, timestamp, layout, cfa_pattern, bits, black and white\n"
    "levels (an image's white_level is its full scale, 255 or 65535), LibRaw's camera matrices\n"
    "(preview only), the measurement image size (width, height: half resolution for Bayer sensors)\n"
    "and linear_hash (FNV-1a of the decoded data).\n"
    "A DNG camera profile (.dcp, recognised by its \"IIRC\" magic) is read strictly instead and its tags printed\n"
    "(matrices, illuminants, HueSatMap range) with, per illuminant, the camera neutral and what it renders as.\n"
    "By its name: *.clf, a Common LUT Format file (read strictly); *.cube, a 3D LUT (title, size,\n"
    "shaper_size, entries, domain_min, domain_max: every row counted and checked); *.icc or *.icm, an\n"
    "ICC profile (size, version, device_class, colour_space, pcs, tags, description; read by lcms2).\n"
    "A file that does not read gives error PARSE_ERROR naming it (and, in a .cube, the line).",
    run_inspect}};

}  // namespace
}  // namespace tristim::cli

// CLI: `tristim apply` — a profile applied to a camera-RGB image, written as float XYZ.
#include <chrono>
#include <cstdint>
#include <iostream>

#include "cli.hpp"
#include "linearise_option.hpp"
#include "patch_args.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim::cli {
namespace {
const char* kApplyUsage =
    "tristim apply <profile.json> <image> --out xyz.tiff|xyz.pfm [--linearisation gamma|sRGB|fitted.json [--full-scale 255]]\n"
    "              [--dark f ...] [--dark-mode per_pixel|per_channel] [--flat f] [--flat-mode pixel|radial]\n"
    "              [--white-reflectance r | r,g,b] [--light-trap x1,y1,x2,y2,x3,y3,x4,y4]\n"
    "  Applies the profile to a camera-RGB image and writes 32-bit float XYZ (TIFF,\n"
    "  uncompressed, or PFM). Input: a RAW file (decoded like the chart: linear, black subtracted,\n"
    "  no white balance), a TIFF/PNG/JPEG (values as stored) or a colour PFM of camera RGB. A\n"
    "  profile fitted with a linearisation stage (fit --linearisation) linearises the stored values\n"
    "  itself; --linearisation is for profiles without one (e.g. a RAW profile on a gamma image).\n"
    "  Abed 2013 App. C step 8: this image's own dark frames, flat field and light trap (the flare of\n"
    "  this scene, measured in the image) calibrate it before the profile, as `sample` does for the chart\n"
    "  (same options, same code).";

int run_apply(const Args& args, std::ostream&) {
  args.allow_only({"out", "linearisation", "full-scale", "dark", "dark-mode", "flat", "flat-mode", "white-reflectance",
                   "light-trap"});
  const bool calibrate = args.has("dark") || args.has("flat") || args.has("light-trap");
  if (args.positional.size() != 2)
    throw Error(ErrorCode::InvalidArgument, "usage: tristim apply <profile.json> <image> --out xyz.tiff|pfm");
  const Profile p = profile_from_json(read_file(args.positional[0]));
  const std::string in_path = args.positional[1];
  Image3f rgb;
  if (ext_of(in_path) == "pfm") {
    if (calibrate)
      throw Error(ErrorCode::InvalidArgument, "--dark, --flat and --light-trap calibrate a RAW or image file, not the PFM '" +
                                                  in_path + "'");
    rgb = read_pfm(read_file(in_path));
  } else {
    // A RAW file: LibRaw's linear camera RGB (black subtracted, no white balance, half size for
    // Bayer sensors), the same data the chart patches are sampled from; a TIFF/PNG/JPEG: its
    // values as stored (recognised by its bytes, like `sample`).
    RawImage raw = load_raw(in_path);
    if (calibrate) raw = apply_calibration(raw, frame_calibration(args, raw, SampleOptions{}));  // App. C steps 1-2, 8
    rgb.width = raw.width;
    rgb.height = raw.height;
    rgb.pixels = std::move(raw.rgb);
  }
  if (p.has_linearisation && args.has("linearisation"))
    throw Error(ErrorCode::InvalidArgument, "the profile has its own linearisation stage (" + p.linearisation.choice.method +
                                                "): --linearisation would apply a second one");
  linearise_image(linearisation_for_image(args), rgb.pixels.data(), rgb.pixels.size() / 3);  // linearise_option.hpp
  const std::string out_path = args.get("out");
  const auto t0 = std::chrono::steady_clock::now();
  const Image3f xyz = apply_profile(p, rgb.pixels.data(), rgb.width, rgb.height);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<uint8_t> bytes;
  const std::string e = ext_of(out_path);
  if (e == "tif" || e == "tiff") bytes = float_tiff(xyz.pixels.data(), xyz.width, xyz.height, "CIE XYZ (tristim " + p.model.id + ")");
  else if (e == "pfm") bytes = float_pfm(xyz.pixels.data(), xyz.width, xyz.height);
  else throw Error(ErrorCode::InvalidArgument, "--out must end in .tiff, .tif or .pfm");
  write_bytes(out_path, bytes.data(), bytes.size());
  std::cerr << "tristim apply: " << xyz.width << "x" << xyz.height << " in " << fmt(ms, 1) << " ms -> " << out_path << "\n";
  return 0;
}

const CommandRegistration reg_apply({"apply", "apply a profile to a linear image -> float XYZ TIFF/PFM", kApplyUsage, run_apply});

}  // namespace
}  // namespace tristim::cli

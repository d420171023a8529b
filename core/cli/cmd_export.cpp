// CLI: `tristim export` — a profile as ICC or .cube (DCP: cmd_dcp.cpp).
#include <iostream>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim::cli {
namespace {
const char* kExportUsage =
    "tristim export --profile p.json (--icc out.icc [--icc-version 4.3|2.4] [--grid 49] |\n"
    "               --cube out.cube [--size 33]) [--rgb-scale S]\n"
    "  ICC input profile (lcms2; matrix/shaper for 3×3 models, AToB0 LUT otherwise) or a .cube\n"
    "  (Resolve convention: 1D shaper u = d^(1/2.2), then a 3D LUT; read by Resolve and OpenColorIO).\n"
    "  Device value d = 1.0 = camera RGB S (default: the profile's largest training value).\n"
    "tristim export --profile p.json --dcp camera.dcp [--second p2.json] [--hue-sat-map 90,30,30]\n"
    "               (--camera-model \"<Make> <Model>\" | --raw photo.dng) [--illuminant D50] [--second-illuminant A]\n"
    "               [--profile-name T] [--copyright T] [--embed-policy allow-copying|embed-if-used|never|no-restrictions]\n"
    "               [--tone-curve linear] [--rgb-scale S]\n"
    "  DNG camera profile (Adobe DNG 1.6; Lightroom, Camera Raw, RawTherapee): ColorMatrix and ForwardMatrix from\n"
    "  the model (its linear part at neutral), with --second a dual-illuminant profile from a second profile of the\n"
    "  same camera under another illuminant, with --hue-sat-map a HueSatMap of hue,saturation,value divisions\n"
    "  carrying what a non-linear model adds. The calibration illuminant is the profile's reference illuminant\n"
    "  (--illuminant / --second-illuminant name it otherwise: A, F2, F11, D50, D55, D65, D75). The camera name\n"
    "  (UniqueCameraModel) comes from --camera-model or the RAW's make and model. `tristim inspect camera.dcp`\n"
    "  reads it back.";

int run_export(const Args& args, std::ostream& out) {
  if (args.has("dcp")) return run_export_dcp(args, out);  // cmd_dcp.cpp
  args.allow_only({"profile", "icc", "cube", "size", "grid", "rgb-scale", "icc-version"});
  const Profile p = profile_from_json(read_file(args.get("profile")));
  if (!args.has("icc") && !args.has("cube")) throw Error(ErrorCode::InvalidArgument, "export needs --icc, --cube or --dcp");
  const double scale = args.get_double("rgb-scale", 0);
  if (args.has("icc")) {
    IccOptions o;
    o.rgb_scale = scale;
    o.grid_points = static_cast<int>(args.get_double("grid", IccOptions{}.grid_points));
    o.version = args.get_double("icc-version", 4.3);
    const auto icc = export_icc(p, o);
    write_bytes(args.get("icc"), icc.data(), icc.size());
  }
  if (args.has("cube")) {
    const std::string cube = export_cube(p, static_cast<int>(args.get_double("size", 33)), scale);
    write_bytes(args.get("cube"), cube.data(), cube.size());
  }
  return 0;
}

const CommandRegistration reg_export({"export", "export a profile as ICC, .cube or DNG camera profile (DCP)", kExportUsage, run_export});

}  // namespace
}  // namespace tristim::cli

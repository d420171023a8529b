// CLI: `tristim idt` — an ACES Input Transform (profile/idt.hpp) written as CLF (profile/clf.hpp).
#include <iostream>
#include <string>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/profile/clf.hpp"
#include "tristim/profile/idt.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::cli {

namespace {

// A file's name without its folders: the recipe in the CLF names inputs, never machine paths.
std::string base_name(const std::string& path) {
  const std::size_t s = path.find_last_of("/\\");
  return s == std::string::npos ? path : path.substr(s + 1);
}

int exactly_one(const Args& args, std::initializer_list<const char*> keys, const std::string& what) {
  int n = 0;
  for (const char* k : keys) n += args.has(k) ? 1 : 0;
  if (n != 1) throw Error(ErrorCode::InvalidArgument, "tristim idt needs exactly one " + what);
  return n;
}

int run_idt(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "sensitivities", "rgb", "reference", "illuminant", "illuminant-file", "training", "reflectances",
                   "adaptation", "out", "json", "matrix"});
  const bool chart = args.has("rgb") || args.has("reference");
  if (chart && !(args.has("rgb") && args.has("reference")))
    throw Error(ErrorCode::InvalidArgument, "--rgb and --reference go together (a chart's camera RGB and its reference)");
  if (chart && (args.has("camera") || args.has("sensitivities")))
    throw Error(ErrorCode::InvalidArgument, "give the camera as --camera, --sensitivities or --rgb/--reference, one of them");
  if (!chart) exactly_one(args, {"camera", "sensitivities"}, "camera: --camera \"<name>\", --sensitivities ssf.csv or --rgb/--reference");
  exactly_one(args, {"illuminant", "illuminant-file"}, "illuminant: --illuminant D55 or --illuminant-file spd.csv");
  if (args.has("training") && args.has("reflectances"))
    throw Error(ErrorCode::InvalidArgument, "give --training 190 or --reflectances r.csv, not both");
  if (chart && (args.has("training") || args.has("reflectances")))
    throw Error(ErrorCode::InvalidArgument, "--training/--reflectances are for sensitivities; a chart trains on its own patches");
  if (args.has("training") && args.get("training") != "190")
    throw Error(ErrorCode::UnknownId, "--training takes 190 (rawtoaces v1's 190 spectra), not '" + args.get("training") + "'");

  const std::string adaptation = args.get("adaptation", "CAT02");
  std::pair<std::string, std::string> illuminant_entry;
  SpectralData illuminant;
  if (args.has("illuminant")) {
    illuminant_entry = {"Illuminant", args.get("illuminant")};
    illuminant = illuminant_spd(args.get("illuminant"));
  } else {
    illuminant_entry = {"IlluminantFile", base_name(args.get("illuminant-file"))};
    illuminant = illuminant_arg(args.get("illuminant-file"));
  }

  IdtFiles files;
  if (chart) {
    const Vec3 white = illuminant_white_XYZ(illuminant);
    const PatchData d = load_pairs(args.get("rgb"), args.get("reference"), white);
    std::vector<Vec3> rgb, xyz;
    for (int i = 0; i < d.rgb.rows(); ++i) {
      rgb.push_back(d.rgb.row(i).transpose());
      xyz.push_back(d.xyz.row(i).transpose());
    }
    files = idt_chart_files(rgb, xyz, white, adaptation, base_name(args.get("rgb")), base_name(args.get("reference")),
                            illuminant_entry);
  } else if (args.has("camera") && args.has("illuminant") && !args.has("reflectances")) {
    files = idt_camera_files(args.get("camera"), args.get("illuminant"), adaptation);  // what the page calls
  } else if (args.has("sensitivities") && args.has("illuminant") && !args.has("reflectances")) {
    const std::string path = args.get("sensitivities");  // the page's uploaded CSV: the same call
    files = idt_sensitivities_files(read_file(path), base_name(path), args.get("illuminant"), adaptation);
  } else {
    IdtOptions o;
    o.adaptation = idt_adaptation(adaptation);
    const bool built_in = args.has("camera");
    const SpectralData ssf = built_in ? camera_ssf(args.get("camera"))
                                      : read_ssf_csv(read_file(args.get("sensitivities")), args.get("sensitivities"));
    const SpectralData training = args.has("reflectances") ? reflectances_arg(args.get("reflectances")) : idt_training_190();
    files = idt_files(idt_from_sensitivities(ssf, illuminant, training, o),
                      idt_recipe(built_in ? std::pair<std::string, std::string>{"Camera", args.get("camera")}
                                          : std::pair<std::string, std::string>{"Sensitivities", base_name(args.get("sensitivities"))},
                                 illuminant_entry,
                                 args.has("reflectances") ? base_name(args.get("reflectances")) : kIdtTraining190, o.adaptation));
  }
  const IdtResult& r = files.result;

  const std::string path = args.get("out");
  write_bytes(path, files.clf.data(), files.clf.size());
  if (args.has("matrix")) write_bytes(args.get("matrix"), files.matrix.data(), files.matrix.size());
  if (args.has("json")) {
    out << files.json;
    return 0;
  }
  const std::string& clf = files.clf;
  const ClfDocument back = read_clf(clf);
  out << "tristim idt: " << path << " (" << clf.size() << " bytes), CLF: camera-native linear RGB -> ACES2065-1\n";
  out << "  white balance (R G B): " << fmt(r.white_balance[0], 6) << " " << fmt(r.white_balance[1], 6) << " "
      << fmt(r.white_balance[2], 6) << "   exposure " << fmt(r.exposure, 6) << "   adaptation " << r.adaptation << "\n";
  out << "  B (white-balanced RGB -> ACES2065-1, rows sum to 1):\n";
  for (int i = 0; i < 3; ++i)
    out << "    " << fmt(r.matrix(i, 0), 6) << " " << fmt(r.matrix(i, 1), 6) << " " << fmt(r.matrix(i, 2), 6) << "\n";
  out << "  fit on " << r.patches << " samples: dE76 mean " << fmt(r.mean_delta_E76) << " max " << fmt(r.max_delta_E76)
      << ", dE00 mean " << fmt(r.mean_delta_E00) << " max " << fmt(r.max_delta_E00) << " (" << r.iterations << " iterations)\n";
  const Vec3 w = apply_clf(back, Vec3(1 / (r.white_balance[0] * r.exposure), 1 / r.exposure, 1 / (r.white_balance[2] * r.exposure)));
  out << "  read back: the camera white maps to ACES " << fmt(w[0], 6) << " " << fmt(w[1], 6) << " " << fmt(w[2], 6) << "\n";
  if (r.status != "ok") out << "  warning: " << r.message << "\n";
  return 0;
}

CommandRegistration reg_idt({"idt", "ACES Input Transform (rawtoaces v1 method) as CLF",
                             "tristim idt (--camera \"<one of the 52>\" | --sensitivities ssf.csv | --rgb patches.csv --reference ref.csv)\n"
                             "            (--illuminant D55 | --illuminant-file spd.csv) [--training 190 | --reflectances r.csv]\n"
                             "            [--adaptation CAT02|Bradford] --out idt.clf [--matrix idt.txt] [--json]\n"
                             "The AMPAS/rawtoaces v1 IDT: white-balanced camera RGB -> ACES2065-1 by a 3x3 whose rows sum to\n"
                             "one, minimising the sum of squared CIE 1976 dE*ab (against the ACES white) over the training\n"
                             "set, with the reference XYZ adapted to the ACES white by CAT02 (default) or Bradford.\n"
                             "From sensitivities (--camera: `tristim list --what cameras`; --sensitivities: wavelength,R,G,B)\n"
                             "the training set is rawtoaces' 190 spectra (--training 190, the default) or --reflectances (a\n"
                             "chart id or a spectral CSV). From a chart: --rgb its linear camera RGB (black subtracted) and\n"
                             "--reference its XYZ or Lab under the illuminant; the white balance comes from its most neutral\n"
                             "bright patch. --out writes the CLF (Info: the recipe; Matrix: exposure * B * diag(white\n"
                             "balance), camera-native RGB in); --matrix also writes the plain 3x3; --json prints \"matrix\" (B),\n"
                             "\"white_balance\" (G = 1) and the fit's errors.",
                             run_idt});

}  // namespace

}  // namespace tristim::cli

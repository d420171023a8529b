// CLI: `tristim export --profile p.json --dcp camera.dcp …` (a DNG camera profile, profile/dcp.hpp)
// and `tristim inspect camera.dcp` (its tags as JSON; `tristim inspect idt.clf` reads a CLF back).
// Called from the export and inspect commands (cmd_export.cpp, cmd_raw.cpp), which own the names.
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/error.hpp"
#include "tristim/io/named_input.hpp"
#include "tristim/profile/clf.hpp"
#include "tristim/profile/dcp.hpp"
#include "tristim/profile/profile.hpp"

namespace tristim::cli {

namespace {

std::uint32_t embed_policy(const std::string& s) {
  if (s == "allow-copying" || s == "0") return 0;
  if (s == "embed-if-used" || s == "1") return 1;
  if (s == "never" || s == "never-embed" || s == "2") return 2;
  if (s == "no-restrictions" || s == "3") return 3;
  throw Error(ErrorCode::InvalidArgument,
              "--embed-policy is allow-copying, embed-if-used, never or no-restrictions (ProfileEmbedPolicy 0..3), not '" + s + "'");
}

std::array<int, 3> divisions(const std::string& text) {
  const std::vector<double> v = numbers(text, "hue-sat-map");
  if (v.size() != 3) throw Error(ErrorCode::InvalidArgument, "--hue-sat-map needs 3 numbers: hue,saturation,value divisions (e.g. 90,30,30)");
  std::array<int, 3> d{};
  for (int i = 0; i < 3; ++i) {
    if (v[i] != std::floor(v[i]) || v[i] < 1 || v[i] > 1000)
      throw Error(ErrorCode::InvalidArgument, "--hue-sat-map divisions must be whole numbers (hue 1..360, saturation 2..256, value 1..256)");
    d[i] = static_cast<int>(v[i]);
  }
  return d;
}

std::string matrix_text(const Mat3& m) {
  std::ostringstream s;
  for (int r = 0; r < 3; ++r) {
    s << "    ";
    for (int c = 0; c < 3; ++c) s << (c ? " " : "") << fmt(m(r, c), 6);
    s << "\n";
  }
  return s.str();
}

}  // namespace

int run_export_dcp(const Args& args, std::ostream& out) {
  args.allow_only({"profile", "dcp", "second", "hue-sat-map", "camera-model", "raw", "illuminant", "second-illuminant",
                   "profile-name", "copyright", "embed-policy", "rgb-scale", "tone-curve"});
  const Profile p1 = profile_from_json(read_file(args.get("profile")));
  Profile p2;
  if (args.has("second")) p2 = profile_from_json(read_file(args.get("second")));
  if (args.has("second-illuminant") && !args.has("second"))
    throw Error(ErrorCode::InvalidArgument, "--second-illuminant goes with --second");
  DcpOptions o;
  if (args.has("camera-model") && args.has("raw"))
    throw Error(ErrorCode::InvalidArgument, "give the camera as --camera-model or --raw, not both");
  if (args.has("raw")) {
    // The camera as LibRaw names it (make + model), the name RawTherapee's own decoder gives too.
    const std::string path = args.get("raw");
    const RawMetadata m =
        parse_named(path, read_file(path), [](const std::uint8_t* d, std::size_t n) { return inspect_raw(d, n); });
    if (m.make.empty() && m.model.empty())
      throw Error(ErrorCode::MissingMetadata, "'" + path + "' names no camera make or model: give --camera-model");
    o.camera_model = m.make.empty() ? m.model : m.model.empty() ? m.make : m.make + " " + m.model;
  } else if (args.has("camera-model")) {
    o.camera_model = args.get("camera-model");
  } else {
    // The profile JSON names no camera. The DCP is still a valid profile, chosen by hand as a
    // custom input profile; only the automatic pick by camera name needs the real name.
    o.camera_model = "tristim camera";
    std::cerr << "tristim export: warning: the profile names no camera: UniqueCameraModel is \"tristim camera\"; give "
                 "--camera-model \"<Make> <Model>\" (e.g. \"Canon EOS 550D\") or --raw <a RAW file of the camera> "
                 "for a DCP that raw converters pick by themselves\n";
  }
  o.illuminant = args.get("illuminant", "");
  o.second_illuminant = args.get("second-illuminant", "");
  o.profile_name = args.get("profile-name", "");
  o.copyright = args.get("copyright", "");
  if (args.has("embed-policy")) o.embed_policy = embed_policy(args.get("embed-policy"));
  if (args.has("hue-sat-map")) o.hue_sat_map = divisions(args.get("hue-sat-map"));
  o.rgb_scale = args.get_double("rgb-scale", 0);
  if (args.has("tone-curve")) {
    if (args.get("tone-curve") != "linear") throw Error(ErrorCode::InvalidArgument, "--tone-curve takes 'linear' (or leave it out: no tone curve)");
    o.linear_tone_curve = true;
  }
  const Dcp d = make_dcp(p1, o, args.has("second") ? &p2 : nullptr);
  const std::vector<std::uint8_t> bytes = write_dcp(d);
  const std::string path = args.get("dcp");
  write_bytes(path, bytes.data(), bytes.size());

  const Dcp back = read_dcp(bytes);  // what a reader gets (rational rounding included)
  const json::Value summary = dcp_json(back);
  out << "tristim export: " << path << " (" << bytes.size() << " bytes), DNG camera profile \"" << d.profile_name << "\"\n";
  out << "  UniqueCameraModel: " << d.unique_camera_model << "\n";
  for (int k = 1; k <= (d.dual() ? 2 : 1); ++k) {
    const int code = k == 1 ? d.illuminant1 : d.illuminant2;
    out << "  CalibrationIlluminant" << k << ": " << code << " (" << dcp_illuminant_name(code) << ", "
        << dcp_illuminant_temperature(code) << " K)\n";
    out << "  ColorMatrix" << k << " (XYZ -> camera):\n" << matrix_text(k == 1 ? back.color_matrix1 : back.color_matrix2);
    out << "  ForwardMatrix" << k << " (white-balanced camera -> XYZ D50):\n"
        << matrix_text(k == 1 ? back.forward_matrix1 : back.forward_matrix2);
    const json::Value& c = summary.at("checks").as_array()[static_cast<std::size_t>(k - 1)];
    if (const json::Value* n = c.find("neutral"); n && n->is_array()) {
      const auto v = n->as_numbers("neutral");
      const auto xy = c.at("neutral_renders_as_xy").as_numbers("xy");
      out << "  camera neutral under illuminant " << k << ": " << fmt(v[0], 4) << " " << fmt(v[1], 4) << " " << fmt(v[2], 4)
          << " -> renders as xy " << fmt(xy[0], 4) << " " << fmt(xy[1], 4) << " (D50: 0.3457 0.3585)\n";
    }
  }
  if (!d.hue_sat_map.empty())
    out << "  ProfileHueSatMap: " << d.hue_sat_map.hue << " hues x " << d.hue_sat_map.sat << " saturations x "
        << d.hue_sat_map.val << " values" << (d.dual() ? ", one table per illuminant" : "") << "\n";
  else if (!model_info(p1.model.id).linear || (args.has("second") && !model_info(p2.model.id).linear))
    out << "  note: the model is not a 3x3 matrix; the DCP carries its linear part at neutral only (add --hue-sat-map "
           "90,30,30 for the rest)\n";
  // RawTherapee 5.9 looks for "<Make> <Model>.dcp" in its own dcpprofiles folder only, with make
  // and model as its decoder (dcraw's, like LibRaw's) names them: checked with the example DNG, whose
  // "Canon EOS Kiss X4.dcp" it then uses for "Camera standard" exactly as the file given by name.
  if (args.has("raw"))
    out << "  RawTherapee: saved as \"" << d.unique_camera_model
        << ".dcp\" (its name for this camera) in its dcpprofiles folder (Debian:\n"
           "  /usr/share/rawtherapee/dcpprofiles) it is used by itself for input profile \"Camera standard\";\n"
           "  anywhere else, choose the file as a custom input profile.\n";
  else
    out << "  RawTherapee uses a DCP by itself (input profile \"Camera standard\") when its dcpprofiles folder holds\n"
           "  \"<Make> <Model>.dcp\" with the camera named as RawTherapee names it (make and model as LibRaw reports\n"
           "  them; --raw <photo> takes them from a RAW): \""
        << d.unique_camera_model << ".dcp\" if that is its name;\n  otherwise choose the file as a custom input profile.\n";
  return 0;
}

bool inspect_dcp(const std::string& path, std::ostream& out) {
  // A Common LUT Format file (tristim idt's output) by its extension: read strictly, as JSON.
  if (ext_of(path) == "clf") {
    const std::string text = read_file(path);
    try {
      out << clf_json(read_clf(text)).dump() << "\n";
    } catch (const Error& e) {
      throw Error(e.code(), "'" + path + "': " + e.what());
    }
    return true;
  }
  {
    std::ifstream in(path, std::ios::binary);
    char head[4] = {};
    if (!in.read(head, 4) || !is_dcp(reinterpret_cast<const std::uint8_t*>(head), 4)) return false;
  }
  const Dcp d = parse_named(path, read_file(path), [](const std::uint8_t* b, std::size_t n) { return read_dcp(b, n); });
  out << dcp_json(d).dump() << "\n";
  return true;
}

}  // namespace tristim::cli

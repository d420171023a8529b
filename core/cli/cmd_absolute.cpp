// CLI: the absolute tele-colorimeter (Guarnera, Bianco & Schettini 2018) and spectral
// sensitivities (Jiang et al. 2013):
//   tristim sensitivities estimate --rgb patches.csv --reflectances spectra.csv --illuminant D65|file.csv [--out ssf.csv]
//   tristim absolute fit --stimuli stimuli.csv [--dark f ...] [--flat f] [--camera NAME | --ssf f.csv] [--out p.json]
//   tristim absolute fit --recipe absrecipe.json [--out p.json]                       (cmd_absolute_fit.cpp)
//   tristim absolute apply <profile.json> <raw>... --out xyz.tiff [--source-map map.tiff]
//   tristim absolute evaluate <profile.json> --stimuli test.csv [<raw>...] [--json]   (cmd_absolute_evaluate.cpp)
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "absolute_cli.hpp"
#include "tristim/absolute/characterise.hpp"
#include "tristim/absolute/fields.hpp"
#include "tristim/absolute/options_table.hpp"
#include "tristim/absolute/sensitivities.hpp"
#include "tristim/absolute/stimuli_file.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/named_input.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::cli {

RawImage load_raw_file(const std::string& path) {
  return parse_named(path, read_file(path), [](const std::uint8_t* d, std::size_t n) { return decode_raw(d, n); });
}

std::string dirname_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string locate_file(const std::string& name, const std::string& base) {
  if (name.empty() || name[0] == '/' || base.empty()) return name;
  return file_exists(base + name) ? base + name : name;
}

std::vector<ExposureSettings> exposure_args(const Args& args, size_t files) {
  const auto given = args.all("exposure");
  if (!given.empty() && given.size() != files)
    throw Error(ErrorCode::InvalidArgument, "give one --exposure t,N[,ISO] per RAW file, in order, or none");
  std::vector<ExposureSettings> out;
  for (const auto& g : given) {
    const auto v = numbers(g, "exposure");
    if (v.size() < 2 || v.size() > 3) throw Error(ErrorCode::InvalidArgument, "--exposure is t,N or t,N,ISO");
    out.push_back({v[0], v[1], v.size() == 3 ? v[2] : 0.0});
  }
  return out;
}

void rethrow_with_exposure_hint(const Error& e) {
  if (e.code() == ErrorCode::MissingMetadata) throw Error(e.code(), std::string(e.what()) + " with --exposure t,N[,ISO]");
  throw e;
}

namespace {

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw Error(ErrorCode::ExportFailed, "cannot write '" + path + "'");
}

void write_text(const std::string& path, const std::string& text) {
  write_bytes(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

// ---- tristim sensitivities estimate ------------------------------------------------------

int run_sensitivities(const Args& args, std::ostream& out) {
  args.allow_only({"rgb", "reflectances", "illuminant", "out", "components", "smoothness", "exclude", "compare"});
  if (args.positional.size() != 1 || args.positional[0] != "estimate")
    throw Error(ErrorCode::InvalidArgument, "usage: tristim sensitivities estimate --rgb patches.csv --reflectances "
                                            "spectra.csv --illuminant D65|file.csv [--out ssf.csv]");
  const std::string rgb_path = args.get("rgb"), refl_arg = args.get("reflectances");
  const PatchTable rgb = read_patch_file(read_file(rgb_path), rgb_path);
  if (!rgb.has_RGB) throw Error(ErrorCode::MissingColumn, rgb_path + ": no R, G, B columns");
  const SpectralData refl = reflectances_arg(refl_arg);
  SensitivityOptions o;
  o.components = static_cast<int>(args.get_double("components", o.components));
  o.smoothness = args.get_double("smoothness", o.smoothness);
  for (const auto& e : args.all("exclude")) o.exclude_cameras.push_back(e);
  // Paired by patch id: the reflectance columns in the order of the RGB rows.
  const SpectralData illuminant = illuminant_arg(args.get("illuminant"));
  const SensitivityEstimate e = estimate_sensitivities_by_id(rgb.ids, rgb.RGB, refl, illuminant, o);
  json::Value s = fields::write(e);  // by its field list: what the page gets
  // How sure the areas are (leave-one-camera-out bases, K ± 1) and whether the camera is unlike the basis.
  const SensitivityUncertainty u = sensitivity_uncertainty_by_id(rgb.ids, rgb.RGB, refl, illuminant, o, e);
  s.set("uncertainty", fields::write(u));  // by its field list: what the page gets
  std::cerr << "tristim sensitivities: A_R/A_G " << e.areas[0] / e.areas[1] << " ± " << 100 * u.u[0] << " %, A_B/A_G "
            << e.areas[2] / e.areas[1] << " ± " << 100 * u.u[1] << " % (k = " << u.coverage << ")\n";
  if (!u.message.empty()) std::cerr << "tristim sensitivities: warning: " << u.message << "\n";
  if (args.has("compare")) {
    const SpectralData truth = camera_ssf(args.get("compare"));
    const auto A = channel_areas(truth);
    s.set("compare", fields::object({{"camera", args.get("compare")},
                                     {"rms_peak_normalised", sensitivity_rms(e.ssf, truth)},
                                     {"area_ratio_R_G", A[0] / A[1]}, {"area_ratio_B_G", A[2] / A[1]}}));
  }
  const std::string csv = sensitivities_to_csv(e.ssf);
  if (args.has("out")) {
    write_text(args.get("out"), csv);
    out << s.dump() << "\n";
  } else {
    out << csv;
    std::cerr << s.dump() << "\n";
  }
  return 0;
}

// ---- tristim absolute apply --------------------------------------------------------------

// The engine's read-out (absolute_readout: the page's pointer) at each point of a CSV (id, x, y[, X,
// Y, Z reference]): {id, the read-out's members, reference, relative_Y_error}.
json::Value point_readout(const std::string& path, const AbsoluteMaps& maps, int window) {
  const TextTable t = parse_delimited(read_file(path), path);
  auto col = [&](const char* name) {
    for (size_t k = 0; k < t.header.size(); ++k)
      if (t.header[k] == name) return static_cast<int>(k);
    return -1;
  };
  const int id = col("id"), x = col("x"), y = col("y"), X = col("X"), Y = col("Y"), Z = col("Z");
  if (x < 0 || y < 0) throw Error(ErrorCode::MissingColumn, path + ": points need x and y columns");
  const FusedLuminance& L = maps.image.luminance;
  json::Value out = json::Value::array();
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const double px = parse_cell(t.rows[r][x], path, t.lines[r], "x"), py = parse_cell(t.rows[r][y], path, t.lines[r], "y");
    if (!(px >= 0 && py >= 0 && px < L.width && py < L.height))
      throw Error(ErrorCode::InvalidArgument, path + ", line " + std::to_string(t.lines[r]) + ": point outside the image");
    const AbsoluteReadout m = absolute_readout(maps, static_cast<int>(px), static_cast<int>(py), window);
    json::Value o = fields::object({{"id", id >= 0 ? t.rows[r][id] : std::to_string(r + 1)}});
    fields::write_members(m, o);
    if (X >= 0 && Y >= 0 && Z >= 0) {
      const Vec3 ref(parse_cell(t.rows[r][X], path, t.lines[r], "X"), parse_cell(t.rows[r][Y], path, t.lines[r], "Y"),
                     parse_cell(t.rows[r][Z], path, t.lines[r], "Z"));
      o.set("reference", fields::write(ref));
      o.set("relative_Y_error", ref[1] > 0 ? (m.XYZ[1] - ref[1]) / ref[1] : NAN);
    }
    out.push(o);
  }
  return out;
}

int run_apply(const Args& args, std::ostream& out) {
  args.allow_only({"out", "source-map", "mode", "exposure", "points", "window"});
  if (args.positional.size() < 3 || args.positional[0] != "apply")
    throw Error(ErrorCode::InvalidArgument, "usage: tristim absolute apply <profile.json> <raw>... --out xyz.tiff");
  AbsoluteProfile p = absolute_profile_from_json(read_file(args.positional[1]));
  if (args.has("mode")) p.fusion = fusion_mode_from_id(args.get("mode"));
  const std::vector<std::string> files(args.positional.begin() + 2, args.positional.end());
  const std::vector<ExposureSettings> given = exposure_args(args, files.size());
  const std::string out_path = args.get("out");
  AbsoluteMaps maps;  // what the page's applyAbsolute gives: the profile as applied, the maps, the frames' names
  if (p.fusion == FusionMode::Weighted) {  // stream: one decoded frame in memory at a time
    maps.profile = p;
    maps.names = files;
    std::unique_ptr<ExposureFusion> fusion;
    for (size_t i = 0; i < files.size(); ++i) {
      const RawImage f = load_raw_file(files[i]);
      check_profile_frame(p, f, series_frame_name(files, i));
      if (!fusion) fusion = std::make_unique<ExposureFusion>(p.normalisation, p.luminance, f.width, f.height);
      try {
        fusion->add(f, frame_exposure(f, series_frame_name(files, i), given.empty() ? ExposureSettings{} : given[i]));
      } catch (const Error& e) {
        rethrow_with_exposure_hint(e);
      }
    }
    maps.image.luminance = fusion->finish();
    luminance_to_XYZ(p, maps.image.luminance.L, maps.image.XYZ);
  } else {  // Algorithm 1 needs every frame at once: the engine's series path (the page's)
    std::vector<RawImage> frames;
    for (const auto& f : files) frames.push_back(load_raw_file(f));
    std::vector<const RawImage*> ptrs;
    for (const auto& f : frames) ptrs.push_back(&f);
    try {
      maps = apply_absolute_series(p, ptrs, {"", given, files});
    } catch (const Error& e) {
      rethrow_with_exposure_hint(e);
    }
  }
  const AbsoluteImage& img = maps.image;
  const FusedLuminance& L = img.luminance;
  write_bytes(out_path, float_tiff(img.XYZ.data(), L.width, L.height, "CIE XYZ, cd/m2 (tristim absolute, Guarnera 2018)"));
  if (args.has("source-map")) {
    // Three samples per pixel: dominant exposure index (-1: none), number of exposures that
    // served the pixel, their bit mask (bit e = exposure e, in the order given).
    std::vector<float> map(L.source.size() * 3);
    for (size_t q = 0; q < L.source.size(); ++q) {
      map[q * 3] = L.source[q] == 255 ? -1.0f : L.source[q];
      int count = 0;
      for (int b = 0; b < kMaxExposures; ++b) count += (L.contributors[q] >> b) & 1;
      map[q * 3 + 1] = static_cast<float>(count);
      map[q * 3 + 2] = L.contributors[q];
    }
    write_bytes(args.get("source-map"), float_tiff(map.data(), L.width, L.height,
                                                   "source exposure index, count, mask (tristim absolute)"));
  }
  // The exposure-selection summary by its field list (what the page's maps summary() gives).
  json::Value s = fields::write(absolute_maps_summary(maps));
  s.set("out", out_path);
  if (args.has("points")) s.set("points", point_readout(args.get("points"), maps, static_cast<int>(args.get_double("window", 5))));
  out << s.dump() << "\n";
  return 0;
}

int run_absolute(const Args& args, std::ostream& out) {
  if (args.positional.empty()) throw Error(ErrorCode::InvalidArgument, "usage: tristim absolute fit|apply|evaluate … (--help)");
  if (args.positional[0] == "fit") {
    if (args.positional.size() != 1) throw Error(ErrorCode::InvalidArgument, "absolute fit takes no positional arguments");
    return run_absolute_fit(args, out);
  }
  if (args.positional[0] == "apply") return run_apply(args, out);
  if (args.positional[0] == "evaluate") return run_absolute_evaluate(args, out);
  throw Error(ErrorCode::InvalidArgument, "unknown subcommand '" + args.positional[0] + "' (fit, apply, evaluate)");
}

const CommandRegistration sensitivities_cmd{Command{
    "sensitivities", "estimate camera spectral sensitivities from one chart photo (Jiang 2013)",
    "usage: tristim sensitivities estimate --rgb patches.csv --reflectances spectra.csv|CHART --illuminant D65|file.csv\n"
    "                                      [--out ssf.csv] [--components 4] [--smoothness 0.001]\n"
    "                                      [--exclude CAMERA ...] [--compare CAMERA]\n"
    "Estimates R, G, B sensitivities (380-780 nm, 5 nm) from per-patch linear camera RGB (black-subtracted,\n"
    "not white balanced, e.g. `tristim sample`) of patches with known reflectances (paired by patch id;\n"
    "a spectral CSV or a chart id) under a known illuminant: a per-channel PCA basis of the 52 built-in\n"
    "cameras' curves (--components K) and a smoothness-constrained least-squares solve (Jiang, Liu, Gu &\n"
    "Süsstrunk 2013). Output CSV wavelength_nm,R,G,B with the three curves scaled by one factor so the\n"
    "largest value is 1 (channel ratios kept); with --out the CSV goes there and a JSON summary (residual,\n"
    "areas, area ratios; --compare: RMS against a built-in camera, each channel peak 1) to stdout.",
    run_sensitivities,
    [] { return option_rows_help("Numbers (--components, --smoothness; the page's boxes)", sensitivity_option_table()); }}};

const CommandRegistration absolute_cmd{Command{
    "absolute", "absolute X, Y, Z in cd/m² from bracketed RAWs (Guarnera 2018)",
    "usage: tristim absolute fit --stimuli stimuli.csv [--dark capN.raw ...] [--flat flat.raw] [--bracket scene.raw ...]\n"
    "                            [--camera NAME | --ssf ssf.csv] [--saturation DN] [--noise-floor DN]\n"
    "                            [--w 10] [--transform T1|To|T2R] [--fusion weighted|recursive] [--out profile.json]\n"
    "                            [--recipe-out absrecipe.json]\n"
    "       tristim absolute fit --recipe absrecipe.json|profile.json [--stimuli s.csv] [--dark f ...] [--flat f]\n"
    "                            [--bracket f ...] [--out profile.json] [--recipe-out absrecipe.json]\n"
    "       tristim absolute apply <profile.json> <raw>... --out xyz.tiff [--source-map map.tiff]\n"
    "                            [--mode weighted|recursive] [--exposure t,N[,ISO] ...] [--points p.csv [--window 5]]\n"
    "       tristim absolute evaluate <profile.json> --stimuli test.csv [<raw>...] [--json] [--white ID|E]\n"
    "                            [--mode weighted|recursive] [--exposure t,N[,ISO] ...]\n"
    "fit: stimuli CSV (column names exact, case-sensitive), one row per stimulus and shot: id, set (luminance|colour; default: luminance when\n"
    "  X = Y = Z within 2 %), exposure_s, f_number, iso (empty: from the RAW metadata), and either file + x,\n"
    "  y, w, h (a region of a RAW, measurement pixels, path relative to the CSV) or R, G, B (black-subtracted\n"
    "  DN, optional falloff f(r)); X, Y, Z measured in cd/m². Lens-cap frames (--dark) give the noise floor,\n"
    "  the training frames the saturation level (measured where the body clips below LibRaw's maximum),\n"
    "  --flat the radial fall-off (eq 7), --camera/--ssf the channel areas A_R, A_G, A_B. The inverse OECF\n"
    "  per channel (eq 8) is fitted across every exposure with t/N² scaling and a reciprocity report; the\n"
    "  colour matrix (eqs 11-15, pattern search) on the colour stimuli. --bracket: the scene's frames (S is\n"
    "  measured on them too, and region rows may name them). --w (more than 2): the zones Z_u, Z_c, Z_o of\n"
    "  section 3.1. Profile JSON to --out (summary on stdout: the report's training figures and fit, as\n"
    "  evaluate --json has them) or to stdout; the profile embeds the recipe (the stimuli rows, the files\n"
    "  named, the settings) and the figures on the training stimuli.\n"
    "fit --recipe: every setting and the stimuli from an absolute recipe (--recipe-out, the page's, or the\n"
    "  one a profile embeds); the files it names are read relative to its folder, or as given on the\n"
    "  command line (--stimuli/--dark/--flat/--bracket replace them). Same recipe and files: same profile.\n"
    "apply: one or more bracketed RAWs of one scene (same camera and size; exposure from the metadata or\n"
    "  --exposure per file) -> 32-bit float TIFF of X, Y, Z in cd/m² (NaN where every exposure clipped);\n"
    "  --source-map: float TIFF of (dominant exposure index or -1, number of exposures used, their bit mask).\n"
    "  weighted (default) streams the frames and weights each usable one by its zone reliability times t/N²;\n"
    "  recursive is the paper's Algorithm 1. The exposure-selection summary as JSON on stdout (the page's:\n"
    "  exposures, pixels each served, Y's range); --points: the page's read-out at each (id, x, y) of a\n"
    "  CSV (mean X, Y, Z over a --window square, L(R, G, B) and the source exposure at the point), with\n"
    "  the relative Y error when the CSV also has X, Y, Z.\n"
    "evaluate: a test scene — a stimuli CSV of per-patch rows (R, G, B as for fit) and region rows (file, x, y,\n"
    "  w, h naming a RAW of the bracket) with their measured X, Y, Z — through the profile: the bracket (the\n"
    "  RAWs given, else the files the region rows name, relative to the CSV) is fused, each region's mean\n"
    "  over its central half compared. Prints the report the page shows: the fit (eq 8 per channel,\n"
    "  reciprocity), the training figures, the section 4.1 figures of the scene — dE94, dE00 (CIELAB white\n"
    "  per eq 16: --white ID the white patch, default the brightest chromatic stimulus; E: X = Y = Z),\n"
    "  NRMSE per X, Y, Z, relative Y error, median absolute error — over every row and over the chromatic\n"
    "  and equal-tristimulus rows apart, the per-point and per-region rows, and the exposure-selection\n"
    "  summary. Text, or JSON with --json.",
    run_absolute,
    [] {
      return option_rows_help("Options of fit (--transform, --fusion, --w, --noise-floor, --saturation; the page's boxes)",
                              absolute_option_table());
    }}};

}  // namespace
}  // namespace tristim::cli

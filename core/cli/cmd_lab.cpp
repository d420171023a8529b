// tristim lab: the colorimetry lab — render (a chart photograph as a real DNG, the truth as JSON).
#include <cmath>
#include <ostream>

#include "cli.hpp"
#include "patch_args.hpp"
#include "tristim/error.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/lab/smi.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::cli {

// Exercises 3-5 (cmd_lab_exercises.cpp): -1 when `sub` is not one of them.
int run_lab_exercise(const std::string& sub, const Args& args, std::ostream& out);

namespace {

// Rows as a JSON array (--json, each by `to_json`) or as CSV: `header`, then `csv_row(row)` per row.
template <class Row, class ToJson, class CsvRow>
int print_rows(const Args& args, std::ostream& out, const std::vector<Row>& rows, ToJson to_json, const char* header,
               CsvRow csv_row) {
  if (args.has("json")) {
    json::Value a = json::Value::array();
    for (const auto& r : rows) a.push(to_json(r));
    out << a.dump(1) << "\n";
  } else {
    out << header << "\n";
    for (const auto& r : rows) out << csv_row(r) << "\n";
  }
  return 0;
}

int run_render(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "sensitivities", "chart", "reflectances", "illuminant", "oecf", "noise", "seed", "exposure",
                   "surface", "falloff", "flare", "corners", "size", "bits", "black", "cfa", "quality", "out", "reference-out"});
  LabRenderOptions o;
  o.camera = args.get("camera", o.camera);
  if (args.has("sensitivities")) {
    const std::string path = args.get("sensitivities");
    o.sensitivities = read_ssf_csv(read_file(path), path);
    if (!args.has("camera")) o.camera = path;
  }
  o.chart = args.get("chart", o.chart);
  if (args.has("reflectances")) {  // a chart of one's own, drawn as a generated grid
    if (args.has("chart")) throw Error(ErrorCode::InvalidArgument, "give --chart or --reflectances, not both");
    o.chart = args.get("reflectances");
    o.reflectances = reflectances_arg(o.chart);
    o.reflectances.names = reflectance_labels(o.chart, o.reflectances.names);  // the file's own spelling
  }
  o.illuminant = args.get("illuminant", o.illuminant);
  o.illuminant_spd = illuminant_arg(o.illuminant);
  if (args.has("surface")) o.surface = parse_choice(args.get("surface"));
  o.exposure = args.get_double("exposure", o.exposure);
  o.falloff = args.get_double("falloff", o.falloff);
  o.flare = args.get_double("flare", o.flare);
  if (args.has("noise")) {
    const auto n = numbers(args.get("noise"), "noise");
    if (n.size() != 2) throw Error(ErrorCode::InvalidArgument, "--noise expects shot,read (shot-noise gain, read noise in DN)");
    o.shot_gain = n[0];
    o.read_noise = n[1];
  }
  if (args.has("seed")) o.seed = static_cast<std::uint64_t>(lab_option("render.seed", args.get_double("seed", 1)));
  if (args.has("corners")) {
    const auto c = numbers(args.get("corners"), "corners");
    if (c.size() != 8) throw Error(ErrorCode::InvalidArgument, "--corners expects x1,y1,x2,y2,x3,y3,x4,y4");
    std::copy(c.begin(), c.end(), o.corners.begin());
  }
  if (args.has("size")) {
    const std::string s = args.get("size");
    const auto x = s.find('x');
    if (x == std::string::npos) throw Error(ErrorCode::InvalidArgument, "--size expects WIDTHxHEIGHT, got '" + s + "'");
    const auto w = numbers(s.substr(0, x), "size"), h = numbers(s.substr(x + 1), "size");
    o.width = static_cast<int>(w.at(0));
    o.height = static_cast<int>(h.at(0));
  }
  o.bits = static_cast<int>(args.get_double("bits", o.bits));
  o.black = static_cast<int>(args.get_double("black", o.black));
  o.cfa = args.get("cfa", o.cfa);
  o.oecf = args.get("oecf", o.oecf);
  o.jpeg_quality = static_cast<int>(args.get_double("quality", o.jpeg_quality));
  const std::string path = args.get("out");
  // The file kind by --out's extension: one of lab_file_kinds() (the page's File picker), by its
  // extension or its id (.jpeg as .jpg); .tif is the short form of .tiff.
  const std::string ext = ext_of(path) == "tif" ? "tiff" : ext_of(path);
  std::string format, names;
  for (const auto& k : lab_file_kinds()) {
    if (ext == k.extension || ext == k.id) format = k.id;
    names += (names.empty() ? "." : ", .") + k.extension;
  }
  if (format.empty())
    throw Error(ErrorCode::InvalidArgument, "--out must end in one of " + names + ", got '" + path + "'");
  const LabRenderFiles r = lab_render_files(o, format);
  write_bytes(path, r.dng.data(), r.dng.size());
  if (args.has("reference-out")) write_bytes(args.get("reference-out"), r.reference.data(), r.reference.size());
  out << r.truth << "\n";
  return 0;
}

int run_smi(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "illuminant", "sensitivities", "json"});
  const SpectralData illuminant = illuminant_arg(args.get("illuminant", "D65"));
  std::vector<CameraQuality> rows;
  if (args.has("sensitivities")) {
    const std::string path = args.get("sensitivities");
    rows.push_back(camera_quality(read_ssf_csv(read_file(path), path), illuminant, args.get("camera", path)));
  } else if (args.has("camera")) {
    for (const auto& name : args.all("camera")) rows.push_back(camera_quality(camera_ssf(name), illuminant, name));
  } else {
    rows = camera_quality_ranking(illuminant);
  }
  return print_rows(args, out, rows, camera_quality_json, "camera,smi,mu_factor,mean_dE", [](const CameraQuality& q) {
    return q.camera + ',' + json::number_text(q.smi) + ',' + json::number_text(q.mu_factor) + ',' + json::number_text(q.mean_dE);
  });
}

int run_overfit(const Args& args, std::ostream& out) {
  args.allow_only({"camera", "illuminant", "sensitivities", "noise", "seed", "json"});
  const SpectralData illuminant = illuminant_arg(args.get("illuminant", "D65"));
  const std::string camera = args.get("camera", "Canon_EOS_5D_Mark_II");
  const SpectralData ssf = args.has("sensitivities") ? read_ssf_csv(read_file(args.get("sensitivities")), args.get("sensitivities"))
                           : camera == "cmf" ? cmf_sensitivities() : camera_ssf(camera);
  OverfitOptions o;
  o.noise = args.get_double("noise", o.noise);
  o.seed = static_cast<std::uint64_t>(args.get_double("seed", 1));
  const auto rows = lab_overfit_exercise(ssf, illuminant, o);
  auto num = [](double v) { return std::isfinite(v) ? json::number_text(v) : std::string(); };
  return print_rows(args, out, rows, overfit_row_json, "model,training,terms,patches,train_dE00,loo_dE00,test_dE00,error",
                    [&](const OverfitRow& r) {
                      return r.model + ',' + r.training + ',' + std::to_string(r.terms) + ',' + std::to_string(r.patches) + ',' +
                             num(r.train_dE00) + ',' + num(r.loo_dE00) + ',' + num(r.test_dE00) + ',' + r.error_code;
                    });
}

int run_metamers(const Args& args, std::ostream& out) {
  args.allow_only({"illuminant", "second", "camera", "sensitivities", "observer", "match", "max-match", "top",
                   "construct", "reflectances", "json"});
  MetamerOptions o;
  o.illuminant = args.get("illuminant", o.illuminant);
  o.illuminant_spd = illuminant_arg(o.illuminant);
  o.second = args.get("second", o.second);
  o.second_spd = illuminant_arg(o.second);
  o.observer = args.get("observer", o.observer);
  o.camera = args.get("camera", "");
  if (args.has("sensitivities")) {
    const std::string path = args.get("sensitivities");
    o.sensitivities = read_ssf_csv(read_file(path), path);
    if (o.camera.empty()) o.camera = path;
  }
  o.match = args.get("match", o.match);
  o.max_match = args.get_double("max-match", o.max_match);
  o.top = static_cast<int>(lab_option("metamers.top", args.get_double("top", o.top)));  // whole, in range, before the cast
  SpectralData set = args.has("reflectances") ? reflectances_arg(args.get("reflectances")) : SpectralData{};
  if (args.has("reflectances")) reflectance_to_fraction(set);
  const MetamerResult r = args.has("construct")
                              ? (set.values.empty() ? construct_metamer(o, args.get("construct"))
                                                    : construct_metamer_in(o, set, args.get("construct")))
                              : (set.values.empty() ? metamer_pairs(o) : metamer_pairs_in(o, set));
  if (args.has("json")) {
    out << metamer_result_json(r).dump(1) << "\n";
    return 0;
  }
  if (!args.has("construct"))
    out << "# " << r.matching << " pairs with dE00 < " << json::number_text(r.max_match) << " for the " << r.match
        << " under " << r.illuminant << " (" << r.compared << " of " << r.all_pairs << " pairs compared)\n";
  if (!r.camera_matrix.empty()) out << "# " << r.camera_matrix << "\n";
  out << "a,b,alpha,viewer,dE00_" << r.illuminant << ",dE00_" << r.second << "\n";
  for (const auto& p : r.pairs)
    for (const auto& v : p.views)
      out << p.a << ',' << p.b << ',' << json::number_text(p.alpha) << ',' << v.viewer << ',' << json::number_text(v.dE00_1)
          << ',' << json::number_text(v.dE00_2) << "\n";
  return 0;
}

/// The lab's number options (lab_option_table: the page's boxes), under the subcommand that takes
/// each, with the bounds the engine enforces.
std::string lab_options_help() {
  std::string s = "Number options (the page's boxes; a value outside [min, max] is refused, INVALID_ARGUMENT):\n", group;
  for (const OptionSpec& o : lab_option_table()) {
    const auto dot = o.name.find('.');
    if (o.name.substr(0, dot) != group) s += "  tristim lab " + (group = o.name.substr(0, dot)) + "\n";
    s += "    " + o.name.substr(dot + 1) + ": " + o.label + (o.unit.empty() ? "" : " (" + o.unit + ")") + ", " +
         lab_option_number(o, o.min) + " to " + lab_option_number(o, o.max) + (o.type == "integer" ? " (whole)" : "") + ", default " +
         lab_option_number(o, o.default_number) + " — " +
         o.description + "\n";
  }
  return s;
}

int run_lab(const Args& args, std::ostream& out) {
  using Run = int (*)(const Args&, std::ostream&);
  static const std::pair<const char*, Run> subs[] = {
      {"render", run_render}, {"smi", run_smi}, {"overfit", run_overfit}, {"metamers", run_metamers}};
  const std::string sub = args.positional.empty() ? "" : args.positional.front();
  if (args.positional.size() > 1) throw Error(ErrorCode::InvalidArgument, "unexpected argument '" + args.positional[1] + "'");
  for (const auto& [name, run] : subs)
    if (sub == name) return run(args, out);
  if (const int rc = run_lab_exercise(sub, args, out); rc >= 0) return rc;
  throw Error(ErrorCode::InvalidArgument,
              "tristim lab needs a subcommand: render, smi, overfit, metamers, shen, table4 or guarnera (got '" + sub + "')");
}

CommandRegistration reg_lab(
    {"lab", "the colorimetry lab: render a chart photograph (DNG/TIFF); camera quality (SMI, mu); exercises",
     "tristim lab render --camera \"<one of the 52>\" --chart cc24|sg140|passport --illuminant D65 --out chart.dng\n"
     "                   [--chart munsell:5R4/14,10YR6/10,5PB|--reflectances my.csv]\n"
     "                   [--sensitivities ssf.csv] [--exposure 0.5] [--noise shot,read] [--seed 1]\n"
     "                   [--surface <method>:<name>=<value>,...] [--falloff 0] [--flare 0]\n"
     "                   [--corners x1,y1,...,x4,y4] [--size 900x600] [--bits 14] [--black 512] [--cfa RGGB]\n"
     "tristim lab render ... --oecf gamma=2.2|sRGB|linear --out chart.tiff\n"
     "  A chart photograph from measured spectra: the chart's reflectances (corrected for the capture geometry\n"
     "  by --surface, Abed 2013) under the illuminant (an id such as D65, A, F2, D5000, or an SPD CSV) through\n"
     "  the camera's sensitivities (`tristim list` names the 52; --sensitivities a CSV of your own), drawn\n"
     "  head-on at 70 % of the frame (or at --corners, measurement-image pixels = half the sensor) into a\n"
     "  Bayer sensor and written as an uncompressed DNG that LibRaw and dcraw_emu open. --exposure: the white\n"
     "  diffuser's G as a fraction of saturation; --noise shot,read: variance g*DN + read^2 per sensor pixel;\n"
     "  --falloff a: 1 - a*r^2 light fall-off (r = 1 at the corners); --flare f: veiling flare, a fraction of\n"
     "  the white. Prints the truth as JSON: corners, white, DNG colour matrix, and per patch the camera RGB\n"
     "  `rgb` (DN above black) that sampling recovers exactly with noise and fall-off off, and the XYZ.\n"
     "  --chart munsell:<chips>: Munsell matte chips (ids such as 5R4/14, or a hue page such as 5R: all its\n"
     "  chips); --reflectances: a spectral CSV/CGATS of your own (or a chart id). Both are drawn as a grid of\n"
     "  columns = ceil(sqrt(1.5 N)) x rows, gap 0, ids from the file; the truth's \"sample_args\" are the\n"
     "  `tristim sample` options (--chart custom --rows --columns --corners) that sample it, \"cell\" per patch.\n"
     "  --reference-out ref.csv: the patches' reference XYZ as a patch CSV (id,X,Y,Z; a grid's cells by cell id)\n"
     "  for tristim fit --xyz.\n"
     "  --out .tiff: an RGB image (one pixel per 2x2 sensor block, no CFA) encoded by --oecf (x = DN/saturation;\n"
     "  gamma=g stores x^(1/g)) in 16 bits; the truth adds `stored` per patch (what sampling the TIFF recovers).\n"
     "tristim lab render ... --oecf sRGB [--quality 95] --out chart.jpg\n"
     "  --out .jpg: the same image in 8 bits as a baseline JPEG (4:4:4, libjpeg quality --quality, default 95);\n"
     "  `stored` per patch is the 8-bit value before compression (sampling the JPEG gives it within 1.5 DN).\n"
     "tristim lab smi [--camera \"<name>\"]... [--illuminant D65] [--sensitivities ssf.csv] [--json]\n"
     "  Camera quality as a colorimeter: the ISO 17321-1 sensitivity metamerism index (SMI = 100 - 5.5 x mean\n"
     "  dE*ab of ColorChecker patches 1-18, ISO 17321-1/Ohta reflectances, CIE 1931, after the white-preserving\n"
     "  3x3 that minimises that mean) and the Vora-Trussell (1993) mu-factor (1 = the Luther condition).\n"
     "  Without --camera or --sensitivities: the 52 built-in cameras, best SMI first. CSV\n"
     "  camera,smi,mu_factor,mean_dE, or with --json an array of {\"camera\",\"smi\",\"mu_factor\",\"mean_dE\"}.\n"
     "tristim lab overfit [--camera \"<name>\"|cmf] [--sensitivities ssf.csv] [--illuminant D65] [--noise 0.002]\n"
     "                    [--seed 1] [--json]\n"
     "  Exercise 2, why a 3x3 is not enough: 3x3, root-polynomial 2, polynomials of 10, 22 and 35 terms fitted by\n"
     "  least squares on a simulated CC24 and SG140 photo (noise sigma relative to the white's G), scored by\n"
     "  mean dE00 on the training patches, leave-one-out and the 1269 Munsell chips held out. --camera cmf: the\n"
     "  CIE 1931 CMFs as the camera (the Luther condition). A model with more terms than patches: TOO_FEW_PATCHES.\n"
     "tristim lab metamers --illuminant D65 --second A [--camera \"<name>\"] [--sensitivities ssf.csv]\n"
     "                     [--observer 1931|1964] [--match observer|camera] [--max-match 0.5] [--top 10]\n"
     "                     [--reflectances <chart id or file>] [--construct <id>] [--json]\n"
     "  The metamerism explorer. Search: pairs of the 1269 Munsell matte chips (or --reflectances) whose dE00\n"
     "  under --illuminant is below --max-match for the observer (or the camera, --match camera), the --top\n"
     "  with the largest dE00 under --second. --construct 5R5/6: a metamer of that chip, the chip plus the\n"
     "  largest metameric black (Wyszecki 1958) keeping it in [0, 1]: an exact match under --illuminant.\n"
     "  With a camera, its figures too (camera RGB -> XYZ by its ISO 17321-1 3x3 under each light).\n"
     "  CSV a,b,alpha,viewer,dE00 under each light; --json adds both spectra, XYZ and Lab under each light.\n"
     "tristim lab shen [--camera \"<name>\"|cmf] [--sensitivities ssf.csv] [--chart cc24|sg140] [--table L|J]\n"
     "                 [--J 3,4,...,12] [--sigma 0,1,2,3] [--table-J 8] [--table-sigma 1] [--seeds 3] [--seed 1] [--json]\n"
     "  Exercise 3, Shen et al. 2008: the OECF from non-grey patches (Shen2008) vs from the greys (grey-based),\n"
     "  on the paper's simulation (eq 29: rho = 22 u^(1/1.8) + noise sigma, 0-255) through the camera under D65;\n"
     "  colorimetric (10-term) and spectral characterisation on the non-grey patches, dE00 means over --seeds\n"
     "  noise realisations. --table L: Tables I-II (L = 0..3 at --table-J, R2 per channel, the paper's rows\n"
     "  beside); --table J: Figs 2-3 (J sweep at L = 1 per sigma). CSV with units in the header; --json the table.\n"
     "tristim lab table4 [--camera Nikon_D850] [--illuminant D50] [--noise 0.001] [--seed 1] [--json]\n"
     "  Exercise 4, Abed et al. 2013 Table IV: every training row (Classic, SG, Custom All, Custom-Matte,\n"
     "  Custom-Glossy, Total; the custom chart = 50 Munsell chips with Table III's matte and glossy rows) x the\n"
     "  five methods (surface table4's simulation), tested on a matte CC24 in the capture geometry; the paper's\n"
     "  cells beside ours.\n"
     "tristim lab guarnera [--table exposure|table4] [--camera \"<name>\"|cmf] [--illuminant D65]\n"
     "                     [--light D65 --light A --light F2] [--training projector --training reflective] [--json]\n"
     "  Exercise 5, Guarnera et al. 2018. exposure: T1, To, T2R and a 10-term polynomial fitted on a CC24, the\n"
     "  Munsell chips' camera RGB and XYZ scaled by k (dE00 vs k: the root-polynomial is exposure-invariant).\n"
     "  table4: the Absolute mode's virtual bracket per light and colour training, fitted as a user would,\n"
     "  applied to one shot, the weighted fusion and Algorithm 1; NRMSE X/Y/Z beside the paper's Table 4.",
     run_lab, lab_options_help});

}  // namespace

}  // namespace tristim::cli

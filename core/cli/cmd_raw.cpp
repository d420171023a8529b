// CLI: `tristim sample <file> --chart ... --corners ...`: camera RAW, TIFF, PNG or JPEG
// (capture/image.hpp decode_any: by the file's bytes, not its name); `tristim inspect`: cmd_inspect.cpp.
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

#include "cli.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/chart/light_trap.hpp"
#include "tristim/error.hpp"
#include "tristim/io/named_input.hpp"
#include "tristim/capture/image.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/number.hpp"

namespace tristim::cli {

RawImage load_raw(const std::string& path) {
  return parse_named(path, read_file(path), [](const std::uint8_t* d, std::size_t n) { return decode_any(d, n); });
}

std::vector<double> numbers(const std::string& text, const std::string& option) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double d = tristim::parse_double(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(d))
      throw Error(ErrorCode::InvalidArgument, "--" + option + " expects comma-separated finite numbers, got '" + text + "'");
    v.push_back(d);
  }
  return v;
}

LayoutOptions layout_options(const Args& args) {
  LayoutOptions layout;
  layout.chart = args.get("chart");
  layout.rows = static_cast<int>(args.get_double("rows", 0));
  layout.columns = static_cast<int>(args.get_double("columns", 0));
  layout.gap = args.get_double("gap", layout.gap);
  if (args.has("margins")) {
    const auto m = numbers(args.get("margins"), "margins");
    if (m.size() != 4) throw Error(ErrorCode::InvalidArgument, "--margins needs 4 numbers: left,top,right,bottom");
    layout.margin_left = m[0];
    layout.margin_top = m[1];
    layout.margin_right = m[2];
    layout.margin_bottom = m[3];
  }
  return layout;
}

/// --dark (repeatable), --dark-mode, --flat, --flat-mode, --white-reflectance and --light-trap as
/// the frame calibration of `image` (Abed 2013 App. C steps 1-2; Guarnera 2018 eq 7): what `sample`
/// and `apply` take (cli.hpp).
FrameCalibration frame_calibration(const Args& args, const RawImage& image, const SampleOptions& options) {
  FrameCalibration cal;
  try {
    cal.dark_mode = dark_mode_from_id(args.get("dark-mode", dark_mode_id(DarkMode::PerPixel)));
  } catch (const Error& e) {
    throw Error(e.code(), std::string("--dark-mode: ") + e.what());
  }
  if (args.has("dark")) {
    std::vector<RawImage> darks;
    for (const auto& f : args.all("dark")) darks.push_back(load_raw(f));
    std::vector<const RawImage*> ptrs;
    for (const auto& d : darks) ptrs.push_back(&d);
    cal.dark = average_dark_frames(ptrs);
  }
  if (args.has("flat")) {
    const RawImage flat = load_raw(args.get("flat"));
    const std::string mode = args.get("flat-mode", "pixel");
    if (mode == "pixel") {
      std::optional<std::array<double, 3>> refl;
      if (args.has("white-reflectance")) {
        const auto r = numbers(args.get("white-reflectance"), "white-reflectance");
        if (r.size() == 1) refl = std::array<double, 3>{r[0], r[0], r[0]};
        else if (r.size() == 3) refl = std::array<double, 3>{r[0], r[1], r[2]};
        else throw Error(ErrorCode::InvalidArgument, "--white-reflectance takes 1 or 3 numbers");
      }
      cal.flat = make_flat_field(flat, cal.dark ? &*cal.dark : nullptr, cal.dark_mode, refl);
    } else if (mode == "radial") {
      cal.falloff = fit_falloff_Guarnera2018(flat, cal.dark ? &*cal.dark : nullptr);
      std::cerr << "fall-off fit (Guarnera 2018 eq 7): p1=" << cal.falloff->p1 << " p2=" << cal.falloff->p2
                << " p3=" << cal.falloff->p3 << " rms_residual=" << cal.falloff->rms_residual << "\n";
    } else {
      throw Error(ErrorCode::InvalidArgument, "--flat-mode is 'pixel' or 'radial'");
    }
  }
  if (args.has("light-trap")) {  // Abed 2013 App. C step 1: flare from an in-scene light trap
    const auto c = numbers(args.get("light-trap"), "light-trap");
    if (c.size() != 8) throw Error(ErrorCode::InvalidArgument, "--light-trap needs 8 numbers: x1,y1,...,x4,y4");
    std::array<double, 8> trap_corners;
    std::copy(c.begin(), c.end(), trap_corners.begin());
    const LightTrap trap = measure_light_trap(image, trap_corners, options, &cal);
    std::cerr << "light trap (Abed 2013 App. C): flare R=" << trap.mean[0] << " G=" << trap.mean[1] << " B=" << trap.mean[2]
              << " DN over " << trap.n << " pixels, subtracted before sampling\n";
    cal = with_light_trap(cal, trap);
  }
  return cal;
}

namespace {

/// The custom grid's and the sampled area's rows (layout_option_table: the page's inputs).
std::string layout_options_help() {
  return option_rows_help("Custom grid and sampled area (the options' bounds; --margins gives the four margin_* in order)",
                          layout_option_table());
}

int run_sample(const Args& args, std::ostream& out) {
  args.allow_only({"chart", "corners", "dark", "dark-mode", "flat", "flat-mode", "white-reflectance",
                   "area", "rows", "columns", "gap", "margins", "light-trap"});
  if (args.positional.size() != 1)
    throw Error(ErrorCode::InvalidArgument, "sample takes exactly one RAW, TIFF, PNG or JPEG file");
  const LayoutOptions layout = layout_options(args);
  std::array<double, 8> corners;
  if (args.has("corners")) {
    const auto c = numbers(args.get("corners"), "corners");
    if (c.size() != 8) throw Error(ErrorCode::InvalidArgument, "--corners needs 8 numbers: x1,y1,...,x4,y4");
    std::copy(c.begin(), c.end(), corners.begin());
  }
  SampleOptions options;
  options.area = args.get_double("area", 0.5);

  const RawImage image = load_raw(args.positional[0]);
  if (!args.has("corners")) {  // detect the chart (issue 12) and say so
    DetectOptions detect;
    detect.charts = {layout.chart};
    detect.custom = layout;
    const ChartCandidate best = detect_charts(image, detect).front();
    corners = best.corners;
    std::cerr << "tristim sample: no --corners given, using the detected " << best.chart << " (confidence "
              << best.confidence << ", orientation " << best.orientation << "): --corners ";
    for (int i = 0; i < 8; ++i) std::cerr << (i ? "," : "") << std::lround(corners[i] * 100) / 100.0;
    std::cerr << "\n";
    // A chart cut by the frame: the patches inside it are sampled, the others named.
    options.partial = !best.missing.empty();
    if (options.partial) {
      std::cerr << "tristim sample: the chart runs off the image; not sampled:";
      for (const auto& id : best.missing) std::cerr << ' ' << id;
      std::cerr << "\n";
    }
  }
  const FrameCalibration cal = frame_calibration(args, image, options);
  const ChartSample s = sample_chart(image, layout, corners, options, &cal);
  out << chart_sample_to_csv(s);
  return 0;
}

const CommandRegistration sample_cmd{Command{
    "sample", "per-patch camera RGB of a chart in a RAW, TIFF, PNG or JPEG file (CSV)",
    "usage: tristim sample <file> --chart <id> [--corners x1,y1,x2,y2,x3,y3,x4,y4]\n"
    "                      [--dark f ...] [--dark-mode per_pixel|per_channel]\n"
    "                      [--flat f] [--flat-mode pixel|radial] [--white-reflectance r | r,g,b]\n"
    "                      [--area 0.5] [--rows N --columns M --gap g --margins l,t,r,b]\n"
    "                      [--light-trap x1,y1,x2,y2,x3,y3,x4,y4]\n"
    "--chart: cc24, cc24-2005, passport, sg140, sg140-2005 or custom (with --rows/--columns,\n"
    "  optional --gap as a fraction of the patch size and --margins as fractions of the chart\n"
    "  width/height; bounds below). --gap also overrides a built-in chart's gap.\n"
    "--corners: the four outer corners of the patch grid, clockwise from the top-left (the\n"
    "  corner at patch A1), in HALF-RESOLUTION image coordinates for Bayer sensors (the\n"
    "  measurement image of `tristim inspect`: width x height; pixel (x, y) covers [x, x+1));\n"
    "  full-resolution pixel coordinates for TIFF, PNG and JPEG images.\n"
    "  Without --corners the chart is detected (`tristim detect`) and the corners used are\n"
    "  printed on stderr; CHART_NOT_FOUND when there is none. A chart cut by the frame: only the\n"
    "  patches inside the image are written, the others named on stderr.\n"
    "--dark: dark frames (repeat the option), averaged, subtracted per pixel or per channel\n"
    "  (--dark-mode, default per_pixel; the recipe's capture.dark_mode; pixel and channel are\n"
    "  accepted as aliases).\n"
    "--flat: flat-field frame: per-pixel gains (Abed 2013 App. C) or a radial fall-off fit\n"
    "  (Guarnera 2018 eq 7; coefficients printed on stderr).\n"
    "--light-trap: the four corners of an in-scene light trap (a black cavity, marked like a patch,\n"
    "  same coordinates as --corners): its mean RGB after the dark frame is the flare, subtracted\n"
    "  per channel before sampling (Abed 2013 App. C step 1); printed on stderr.\n"
    "--area: sampled fraction of each patch's width and height (default 0.5: the central quarter).\n"
    "Output CSV: patch,R,G,B,R_std,G_std,B_std,n,flags — for a RAW, linear, black-subtracted DN (no\n"
    "white balance, no matrix); for a TIFF/PNG/JPEG, the values as stored (0..255 or 0..65535, not\n"
    "linearised: see `tristim inspect`'s format and bits); flags: saturated;dark;nonuniform.",
    run_sample, layout_options_help}};

}  // namespace
}  // namespace tristim::cli

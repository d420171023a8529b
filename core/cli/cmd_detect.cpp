// CLI: `tristim detect <raw> [--chart cc24|passport|sg140|…]` — automatic chart detection (issue 12).
#include <iostream>
#include <ostream>

#include "cli.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/detect.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/error.hpp"
#include "tristim/io/json.hpp"

namespace tristim::cli {
namespace {

int run_detect(const Args& args, std::ostream& out) {
  args.allow_only({"chart", "rows", "columns", "margins", "min-confidence", "seed", "box"});
  if (args.positional.size() != 1) throw Error(ErrorCode::InvalidArgument, "detect takes exactly one image file");
  DetectOptions options;
  if (args.has("chart")) {
    options.custom = layout_options(args);
    options.charts = {options.custom.chart};
  }
  options.min_confidence = args.get_double("min-confidence", options.min_confidence);
  if (args.has("seed")) options.seed = numbers(args.get("seed"), "seed");
  if (args.has("box")) options.box = numbers(args.get("box"), "box");
  const RawImage image = load_raw(args.positional[0]);
  try {
    out << candidates_to_json(detect_charts(image, options));
  } catch (const Error& e) {
    if (e.code() != ErrorCode::ChartNotFound) throw;
    // The JSON says why as well (stdout); the error line follows on stderr, exit status 1.
    out << "{\"candidates\":[],\"error\":\"" << e.code_name() << "\",\"why\":" << json::Value(std::string(e.what())).dump()
        << "}\n";
    throw;
  }
  return 0;
}

const CommandRegistration detect_cmd{Command{
    "detect", "find colour charts in a RAW file: corners, orientation, confidence (JSON)",
    "usage: tristim detect <raw> [--chart cc24|cc24-2005|passport|sg140|sg140-2005|custom]\n"
    "                      [--rows N --columns M [--margins l,t,r,b]] [--min-confidence 0.5]\n"
    "                      [--seed x,y | --box x0,y0,x1,y1]\n"
    "Finds the chart's patch grid in the linear image (no white balance needed) and prints\n"
    "{\"candidates\": [{\"chart\", \"corners\": [[x,y] x 4], \"confidence\", \"orientation\", ...}]},\n"
    "best first, one candidate per chart found. corners: the outer corners of the patch grid,\n"
    "A1's first, clockwise, in the coordinates `tristim sample --corners` takes (half resolution\n"
    "for Bayer sensors). orientation: clockwise rotation of the chart, 0/90/180/270 (A1 -> A6\n"
    "pointing right, down, left, up); angle: the same in degrees. Each candidate also carries the\n"
    "fitted gap between patches, the edge fit's RMS in px and per-patch residuals of a 3x3 fit\n"
    "of the camera RGB to the chart's reference colours, and \"missing\": the patches outside the\n"
    "image when the chart is cut by the frame (found when half of its patches or more are inside;\n"
    "its corners then may lie outside the image; `tristim sample` samples the rest).\n"
    "--chart: which layout to look for (default: cc24 and sg140; a Passport's classic side is\n"
    "  found as cc24, or as passport when asked for). custom needs --rows/--columns; its\n"
    "  orientation cannot be told from colours and is reported as orientation_resolved false.\n"
    "--seed x,y: a point on or near the chart (image pixels, as corners): detection runs in\n"
    "  windows centred on it, from 1/4 of the image up to all of it, and keeps the chart near it\n"
    "  (a small chart is then searched at full resolution).\n"
    "--box x0,y0,x1,y1: a rough box around the chart; detection runs within it (+10% each side).\n"
    "Exit status 1 with CHART_NOT_FOUND when no chart reaches --min-confidence; stdout then holds\n"
    "{\"candidates\": [], \"error\": \"CHART_NOT_FOUND\", \"why\": \"...\"}: what the detector saw\n"
    "(\"the largest flat regions form no grid\", \"a grid of 4x6 found but its colours do not fit\n"
    "the cc24 chart (...)\", ...).",
    run_detect}};

}  // namespace
}  // namespace tristim::cli

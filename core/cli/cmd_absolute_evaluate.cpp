// CLI: `tristim absolute evaluate <profile.json> --stimuli test.csv [<raw>...] [--json]` — a test
// scene through an absolute profile: the report the page shows (absolute_report, tristim/absolute/
// report.hpp), as text or JSON.
#include <iostream>

#include "absolute_cli.hpp"
#include "tristim/error.hpp"

namespace tristim::cli {

int run_absolute_evaluate(const Args& args, std::ostream& out) {
  args.allow_only({"stimuli", "json", "white", "mode", "exposure"});
  if (args.positional.size() < 2)
    throw Error(ErrorCode::InvalidArgument, "usage: tristim absolute evaluate <profile.json> --stimuli test.csv [<raw>...] [--json]");
  const AbsoluteProfile profile = absolute_profile_from_json(read_file(args.positional[1]));
  const std::string csv = args.get("stimuli");
  const std::vector<AbsoluteStimulus> rows = read_absolute_stimuli(read_file(csv), csv);
  // The bracket: the RAWs given (named as given), else the files the region rows name (named as
  // the rows spell them, read relative to the CSV), in the order they first appear.
  std::vector<std::string> names(args.positional.begin() + 2, args.positional.end()), paths = names;
  if (names.empty())
    for (const auto& r : rows)
      if (r.region() && find_frame(names, r.file) < 0) {
        names.push_back(r.file);
        paths.push_back(locate_file(r.file, dirname_of(csv)));
      }
  std::vector<RawImage> decoded;
  for (const auto& p : paths) decoded.push_back(load_raw_file(p));
  std::vector<const RawImage*> frames;
  for (const auto& f : decoded) frames.push_back(&f);
  AbsoluteApplyOptions o;
  o.mode = args.get("mode", "");
  o.exposures = exposure_args(args, frames.size());
  o.names = names;
  AbsoluteEvaluateOptions e;
  e.white = args.get("white", "");
  AbsoluteReport report;
  try {
    if (frames.empty()) {
      report = absolute_report(profile, nullptr, rows, e);
    } else {
      const AbsoluteMaps maps = apply_absolute_series(profile, frames, o);
      report = absolute_maps_report(maps, rows, e);
    }
  } catch (const Error& err) {
    rethrow_with_exposure_hint(err);
  }
  if (args.has("json")) out << absolute_report_json(report).dump(2) << "\n";
  else out << absolute_report_text(report);
  return 0;
}

}  // namespace tristim::cli

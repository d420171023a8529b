// CLI support for `--bootstrap N [--seed S] [--level L]` of fit and compare (bootstrap_args.cpp):
// the options, the per-patch pixel statistics of a sampled patch file, progress on stderr, and the
// "ci" objects written next to each mean (evaluation/bootstrap.hpp).
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "tristim/evaluation/bootstrap.hpp"
#include "tristim/io/json.hpp"

namespace tristim::cli {

/// The option names; add them to a command's allow_only list.
const std::vector<std::string>& bootstrap_option_names();  // bootstrap, seed, level

/// BootstrapOptions from --bootstrap (1…100000), --seed (a whole number >= 0, default 1) and
/// --level (in (0, 1), default 0.95); Error(InvalidArgument) naming the option otherwise. With
/// `rgb_path` a patch file carrying R_std,G_std,B_std,n columns (what `sample` writes), each of
/// `ids`' pixel statistics are set so the pixels are resampled too (only when `linear`: the
/// statistics are of the stored values). Progress goes to stderr as "tristim <command>: ...".
BootstrapOptions bootstrap_options(const Args& args, const std::string& command, const std::string& rgb_path,
                                   const std::vector<std::string>& ids, bool linear);

/// Each patch's pixel spread (R, G, B) and pixel count by patch key: a patch file's R_std, G_std,
/// B_std and n columns, or the patches `fit --raw` sampled itself.
using PixelStats = std::map<std::string, std::pair<Vec3, double>>;

/// Sets `b`'s pixel statistics for `ids` from `stats` when every id has them (otherwise `b` keeps
/// none and the resampling is over the patches only).
void set_pixel_stats(BootstrapOptions& b, const std::vector<std::string>& ids, const PixelStats& stats);

/// `summary` (a summary_json object) with "ci" set next to its "mean".
json::Value with_ci(const json::Value& summary, const Interval& ci);

}  // namespace tristim::cli

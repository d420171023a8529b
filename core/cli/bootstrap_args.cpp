// CLI support for --bootstrap (bootstrap_args.hpp).
#include "bootstrap_args.hpp"

#include <iostream>
#include <map>
#include <memory>

#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"

namespace tristim::cli {

const std::vector<std::string>& bootstrap_option_names() {
  static const std::vector<std::string> names{"bootstrap", "seed", "level"};
  return names;
}

BootstrapOptions bootstrap_options(const Args& args, const std::string& command, const std::string& rgb_path,
                                   const std::vector<std::string>& ids, bool linear) {
  BootstrapOptions b;
  const double n = args.get_double("bootstrap", 1000);
  if (!(n >= 1 && n <= 100000 && n == static_cast<int>(n)))
    throw Error(ErrorCode::InvalidArgument, "--bootstrap must be a whole number of resamples from 1 to 100000, got '" +
                                                args.get("bootstrap") + "'");
  b.resamples = static_cast<int>(n);
  const double seed = args.get_double("seed", 1);
  if (!(seed >= 0 && seed <= 9007199254740992.0 && seed == static_cast<double>(static_cast<uint64_t>(seed))))
    throw Error(ErrorCode::InvalidArgument, "--seed must be a whole number >= 0, got '" + args.get("seed") + "'");
  b.seed = static_cast<uint64_t>(seed);
  b.level = args.get_double("level", 0.95);
  if (!(b.level > 0 && b.level < 1))
    throw Error(ErrorCode::InvalidArgument, "--level must lie between 0 and 1 (e.g. 0.95), got '" + args.get("level") + "'");
  if (linear && !rgb_path.empty()) {
    const TextTable t = parse_delimited(read_file(rgb_path), rgb_path);
    const int id = t.find({"patch", "id", "sample_id", "sample_name", "name", "sample"});
    const int c[4] = {t.find({"R_std"}), t.find({"G_std"}), t.find({"B_std"}), t.find({"n"})};
    if (id >= 0 && c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[3] >= 0) {
      PixelStats stats;
      for (size_t r = 0; r < t.rows.size(); ++r) {
        Vec3 s;
        for (int k = 0; k < 3; ++k) s[k] = parse_cell(t.rows[r][c[k]], rgb_path, t.lines[r], t.header[c[k]]);
        stats[normalise_patch_id(t.rows[r][id])] = {s, parse_cell(t.rows[r][c[3]], rgb_path, t.lines[r], "n")};
      }
      set_pixel_stats(b, ids, stats);
    }
  }
  auto last = std::make_shared<int>(0);  // the last tenth reported
  b.progress = [command, last](int done, int total) {
    if (done * 10 / total > *last) {
      *last = done * 10 / total;
      std::cerr << "tristim " << command << ": bootstrap " << done << "/" << total << "\n";
    }
    return true;
  };
  return b;
}

void set_pixel_stats(BootstrapOptions& b, const std::vector<std::string>& ids, const PixelStats& stats) {
  for (const auto& i : ids)
    if (!stats.count(i)) return;
  b.pixel_std.resize(static_cast<Eigen::Index>(ids.size()), 3);
  b.pixel_count.clear();
  for (size_t i = 0; i < ids.size(); ++i) {
    b.pixel_std.row(static_cast<Eigen::Index>(i)) = stats.at(ids[i]).first.transpose();
    b.pixel_count.push_back(stats.at(ids[i]).second);
  }
}

json::Value with_ci(const json::Value& summary, const Interval& ci) { return summary_with_ci(summary, ci); }

}  // namespace tristim::cli

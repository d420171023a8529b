// CLI entry points of the share commands (cmd_share.cpp) that other commands call.
#pragma once
#include <iosfwd>

#include "cli.hpp"

namespace tristim::cli {

/// `tristim fit --project p.tristim [--out profile.json]`: the profile of a project file, recomputed
/// from its recipe and patch data (tristim/share/link.hpp), printed or written to --out; its
/// verdict against the project's expected results goes to stderr.
int run_fit_project(const Args& args, std::ostream& out);

}  // namespace tristim::cli

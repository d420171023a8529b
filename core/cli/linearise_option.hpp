// CLI support for the linearisation stage, shared by `tristim linearise`, `tristim spectral` and
// the `--linearisation` option of fit / compare / apply (core/cli/cmd_linearise.cpp).
#pragma once
#include <string>
#include <vector>

#include "cli.hpp"
#include "tristim/linearisation/linearisation.hpp"

namespace tristim::cli {

/// The options linearisation_option() reads; add them to a command's allow_only list.
const std::vector<std::string>& linearisation_option_names();  // linearisation, reflectances, full-scale

/// `--linearisation <id>[:name=value,...]` (fitted on these patches) or `--linearisation
/// file.json` (a fitted linearisation: the output of `tristim linearise --json`, or its
/// "linearisation" object): returns it and replaces `rgb` by the linearised values. Without the
/// option: identity, rgb unchanged. Methods that need reflectances read `--reflectances` (a
/// chart id or a spectral file); `--full-scale` sets the encoding's full scale (default: see
/// default_full_scale). Warnings go to stderr as "tristim <command>: warning: ...".
Linearisation linearisation_option(const Args& args, const std::string& command, const std::vector<std::string>& ids,
                                   PatchMatrix& rgb, const PatchMatrix& reference_XYZ, const Vec3& white);

/// For images (apply): a fitted JSON, or a method that needs no data (identity, gamma, sRGB)
/// with --full-scale (default 255). Without the option: identity.
Linearisation linearisation_for_image(const Args& args);

/// The linearisation table as a --help section (methods_help), each row with its reference.
std::string linearisations_help();

/// The encoding's full scale when none is given: 1 if every value is <= 1, 255 if <= 255,
/// 65535 if <= 65535, else the largest value.
double default_full_scale(const PatchMatrix& rgb);

}  // namespace tristim::cli

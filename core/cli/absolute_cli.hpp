// What the `tristim absolute` subcommands share (cmd_absolute.cpp: apply and the command itself;
// cmd_absolute_fit.cpp: fit; cmd_absolute_evaluate.cpp: evaluate).
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "cli.hpp"
#include "tristim/absolute/characterise.hpp"

namespace tristim::cli {

/// Decodes a RAW file (decode_raw: the absolute chain reads sensor values only); errors name the path.
RawImage load_raw_file(const std::string& path);
/// The folder of a path with its trailing '/' ("" for a bare file name).
std::string dirname_of(const std::string& path);
/// Where a file a CSV or recipe names is read: an absolute path as is, else relative to `base`
/// (the CSV's or recipe's folder) when it is there, else as given (relative to the working folder).
std::string locate_file(const std::string& name, const std::string& base);
/// --exposure t,N[,ISO], one per RAW file in order (none: every exposure from the metadata).
std::vector<ExposureSettings> exposure_args(const Args& args, size_t files);
/// A hint for the command line on a MissingMetadata error ("… with --exposure t,N[,ISO]").
[[noreturn]] void rethrow_with_exposure_hint(const Error& e);

int run_absolute_fit(const Args& args, std::ostream& out);       // cmd_absolute_fit.cpp
int run_absolute_evaluate(const Args& args, std::ostream& out);  // cmd_absolute_evaluate.cpp

}  // namespace tristim::cli

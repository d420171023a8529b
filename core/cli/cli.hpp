// tristim CLI: one file per command group (cmd_<topic>.cpp), each registering its commands.
#pragma once
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace tristim {
struct RawImage;
struct SpectralData;
struct LayoutOptions;
struct MethodInfo;
struct OptionSpec;
struct FrameCalibration;
struct SampleOptions;
}

namespace tristim::cli {

/// Parsed `--key value` / `--flag` options and positional arguments.
struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> options;  // repeated options keep every value
  /// Every option (key, value) in command-line order: for options that belong to the one before
  /// them (fit's per-image --dark/--flat after each --raw).
  std::vector<std::pair<std::string, std::string>> in_order;
  bool has(const std::string& key) const { return options.count(key) > 0; }
  /// The option's last value; throws Error(InvalidArgument) if absent and no default given.
  std::string get(const std::string& key) const;
  std::string get(const std::string& key, const std::string& fallback) const;
  std::vector<std::string> all(const std::string& key) const;
  double get_double(const std::string& key, double fallback) const;
  /// Throws Error(InvalidArgument) naming any option not in `known`.
  void allow_only(const std::vector<std::string>& known) const;
};

struct Command {
  std::string name;
  std::string summary;  // one line, for `tristim --help`
  std::string usage;    // full help text for `tristim <name> --help`
  std::function<int(const Args&, std::ostream& out)> run;
  /// Printed by --help after `usage`: the methods the command takes, each with the reference its
  /// engine table gives (methods_help), so a citation is written once, in the table.
  std::function<std::string()> details{};
};

/// Adds a command; called from static initialisers in cmd_*.cpp via CommandRegistration.
void register_command(Command command);
const std::map<std::string, Command>& commands();

struct CommandRegistration {
  explicit CommandRegistration(Command command) { register_command(std::move(command)); }
};

/// A --help section: `title`, then one line per row, "id: label — reference" (the row's own
/// reference, from its engine table).
std::string methods_help(const std::string& title, const std::vector<MethodInfo>& rows);
/// A --help section of OptionSpec rows (an engine table of a command's numbers, as the page's
/// inputs read it): "name: label (unit), min to max, default d — description"; a choice row lists
/// its choices.
std::string option_rows_help(const std::string& title, const std::vector<OptionSpec>& rows);
/// The characterisation models (model_table(), duplicates named as such) as a methods_help section.
std::string models_help();

/// Reads a whole file as bytes/text; Error(InvalidArgument) naming the path if unreadable.
std::string read_file(const std::string& path);

/// Whether `path` opens for reading.
bool file_exists(const std::string& path);
/// --illuminant's value: a readable spectral CSV file (read_illuminant_csv) or a built-in id
/// (D65, A, D<CCT>, ...; illuminant_spd).
SpectralData illuminant_arg(const std::string& value);
/// --reflectances' value: a built-in chart id (chart_reflectances, names as normalised patch ids)
/// or a readable patch file with spectra (read_reflectance_file); Error(UnknownId) otherwise.
SpectralData reflectances_arg(const std::string& value);
/// The names to write for columns `names` of reflectances_arg(value): a file's own spelling of
/// each patch id (its column or row "A01", where the data's names are the keys "A1"); a chart's ids.
std::vector<std::string> reflectance_labels(const std::string& value, const std::vector<std::string>& names);

/// Decodes a RAW file (cmd_raw.cpp); errors name the path.
RawImage load_raw(const std::string& path);

/// --dark (repeatable), --dark-mode, --flat, --flat-mode, --white-reflectance and --light-trap
/// x1,y1,…,x4,y4 (measured on `image` with `options`' sampled area) as a frame calibration
/// (cmd_raw.cpp): the options `sample` and `apply` share.
FrameCalibration frame_calibration(const Args& args, const RawImage& image, const SampleOptions& options);

/// --chart, --rows, --columns, --margins l,t,r,b as chart layout options (cmd_raw.cpp).
LayoutOptions layout_options(const Args& args);

/// `tristim export --dcp …` (cmd_dcp.cpp): run_export hands every option to it when --dcp is given.
int run_export_dcp(const Args& args, std::ostream& out);
/// `tristim inspect` of a DNG camera profile (cmd_dcp.cpp): prints its tags as JSON and returns
/// true when the file starts like a DCP (or, named *.clf, a Common LUT Format file: clf_json);
/// returns false, having printed nothing, otherwise.
bool inspect_dcp(const std::string& path, std::ostream& out);

/// Comma-separated finite numbers of option --`option`; Error(InvalidArgument) naming it otherwise.
std::vector<double> numbers(const std::string& text, const std::string& option);

}  // namespace tristim::cli

// tristim CLI entry point: dispatch to a registered command; errors become one line on stderr.
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/methods.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/number.hpp"
#include "tristim/memory.hpp"
#include "tristim/version.hpp"

namespace tristim::cli {

namespace {
std::map<std::string, Command>& registry() {
  static std::map<std::string, Command> r;
  return r;
}
}  // namespace

void register_command(Command command) { registry()[command.name] = std::move(command); }

const std::map<std::string, Command>& commands() { return registry(); }

std::string methods_help(const std::string& title, const std::vector<MethodInfo>& rows) {
  std::string s = title + ":\n";
  for (const auto& r : rows) s += "  " + r.id + ": " + r.label + " — " + r.reference + "\n";
  return s;
}

/// A --help section of OptionSpec rows (an engine table of a command's numbers, as the page's
/// inputs read it): "name: label (unit), min to max, default d — description"; a choice row lists
/// its choices.
std::string option_rows_help(const std::string& title, const std::vector<OptionSpec>& rows) {
  std::ostringstream s;
  s << title << ":\n";
  for (const OptionSpec& o : rows) {
    s << "  " << o.name << ": " << o.label << (o.unit.empty() ? "" : " (" + o.unit + ")") << ", ";
    if (o.type == "choice" || o.type == "text") {
      for (size_t k = 0; k < o.choices.size(); ++k) s << (k ? " | " : "") << o.choices[k];
      s << (o.choices.empty() ? "" : ", ") << "default " << o.default_text;
    } else {
      s << (o.min_exclusive ? "more than " : "") << o.min << " to " << o.max << ", default " << o.default_number;
    }
    s << " — " << o.description << "\n";
  }
  return s.str();
}

std::string models_help() {
  std::vector<MethodInfo> rows;
  for (const auto& m : model_table())
    rows.push_back({m.id, m.label + (m.duplicate_of.empty() ? "" : " (same as " + m.duplicate_of + ")"), m.reference, {}});
  return methods_help("Models (--model; tristim models)", rows);
}

std::string Args::get(const std::string& key) const {
  auto it = options.find(key);
  if (it == options.end() || it->second.empty())
    throw Error(ErrorCode::InvalidArgument, "missing required option --" + key);
  return it->second.back();
}
std::string Args::get(const std::string& key, const std::string& fallback) const {
  auto it = options.find(key);
  return (it == options.end() || it->second.empty()) ? fallback : it->second.back();
}
std::vector<std::string> Args::all(const std::string& key) const {
  auto it = options.find(key);
  return it == options.end() ? std::vector<std::string>{} : it->second;
}
double Args::get_double(const std::string& key, double fallback) const {
  if (!has(key)) return fallback;
  const std::string s = get(key);
  char* end = nullptr;
  const double v = tristim::parse_double(s.c_str(), &end);
  if (s.empty() || *end != '\0')
    throw Error(ErrorCode::InvalidArgument, "--" + key + " expects a number, got '" + s + "'");
  return v;
}
void Args::allow_only(const std::vector<std::string>& known) const {
  for (const auto& kv : options) {
    bool ok = false;
    for (const auto& k : known) ok = ok || k == kv.first;
    if (!ok) throw Error(ErrorCode::InvalidArgument, "unknown option --" + kv.first);
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::InvalidArgument, "cannot open '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool file_exists(const std::string& path) { return static_cast<bool>(std::ifstream(path)); }

SpectralData illuminant_arg(const std::string& value) {
  if (file_exists(value)) return read_illuminant_csv(read_file(value), value);
  return illuminant_spd(value);
}

SpectralData reflectances_arg(const std::string& value) {
  for (const auto& c : list_charts())
    if (c.id == value) {
      SpectralData s = chart_reflectances(value);
      for (auto& n : s.names) n = normalise_patch_id(n);
      return s;
    }
  if (!file_exists(value))
    throw Error(ErrorCode::UnknownId, "--reflectances '" + value + "' is neither a chart id nor a readable file");
  return read_reflectance_file(read_file(value), value);
}

std::vector<std::string> reflectance_labels(const std::string& value, const std::vector<std::string>& names) {
  for (const auto& c : list_charts())
    if (c.id == value) return names;
  return patch_labels(read_patch_file(read_file(value), value), names);
}

}  // namespace tristim::cli

namespace {
void print_help(std::ostream& out) {
  out << "tristim " << tristim::kVersion << " — turn a digital camera into a colorimeter\n\n"
      << "usage: tristim <command> [options]   (tristim <command> --help for details)\n\ncommands:\n";
  for (const auto& kv : tristim::cli::commands())
    out << "  " << kv.first << std::string(kv.first.size() < 12 ? 12 - kv.first.size() : 1, ' ')
        << kv.second.summary << "\n";
}

// Options that take no value. Everything else of the form --key takes the next argument.
bool is_flag(const std::string& key) {
  return key == "help" || key == "json" || key == "version" || key == "no-header" || key == "no-loo" || key == "de-rms" ||
         key == "per-wavelength" || key == "list" || key == "payload" ||
         key == "ridge" || key == "use-greys";
}
}  // namespace

int main(int argc, char** argv) {
  using namespace tristim;
  using namespace tristim::cli;
  std::ios::sync_with_stdio(false);
  keep_freed_memory();  // decoded frames reuse freed memory instead of fresh pages (memory.hpp)
  if (argc < 2) {
    print_help(std::cerr);
    return 2;
  }
  const std::string first = argv[1];
  if (first == "--version" || first == "version") {
    std::cout << "tristim " << kVersion << "\n";
    return 0;
  }
  if (first == "--help" || first == "-h" || first == "help") {
    print_help(std::cout);
    return 0;
  }
  auto it = commands().find(first);
  if (it == commands().end()) {
    std::cerr << "tristim: unknown command '" << first << "' (try tristim --help)\n";
    return 2;
  }
  try {
    Args args;
    for (int i = 2; i < argc; ++i) {
      std::string a = argv[i];
      if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
        std::string key = a.substr(2), value;
        const auto eq = key.find('=');
        if (eq != std::string::npos) {
          value = key.substr(eq + 1);
          key = key.substr(0, eq);
        } else if (!is_flag(key)) {
          if (i + 1 >= argc)
            throw Error(ErrorCode::InvalidArgument, "option --" + key + " needs a value");
          value = argv[++i];
        }
        args.options[key].push_back(value);
        args.in_order.emplace_back(key, value);
      } else {
        args.positional.push_back(a);
      }
    }
    if (args.has("help")) {
      std::cout << it->second.usage << "\n";
      if (it->second.details) std::cout << "\n" << it->second.details();
      return 0;
    }
    return it->second.run(args, std::cout);
  } catch (const Error& e) {
    std::cerr << "tristim " << first << ": error " << e.code_name() << ": " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "tristim " << first << ": internal error: " << e.what() << "\n";
    return 3;
  }
}

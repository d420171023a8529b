// CSV and CGATS.17 readers (see tristim/io/patch_files.hpp for the rules and error codes).
#include "tristim/io/patch_files.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "tristim/colorimetry/spectra.hpp"
#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/number.hpp"

namespace tristim {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string trim(std::string_view s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

std::string where(std::string_view source, int line) {
  return std::string(source.empty() ? "input" : source) + ", line " + std::to_string(line);
}

[[noreturn]] void too_large(std::string_view source, const std::string& what, std::size_t limit) {
  throw Error(ErrorCode::LimitExceeded, std::string(source.empty() ? "input" : source) + ": " + what +
                                            ", over the limit of " + std::to_string(limit));
}

/// Splits text into lines (\n, \r\n or \r), dropping a UTF-8 BOM: views into `text`, nothing
/// copied. Error(LimitExceeded) for text over limits::kMaxTextFileBytes or with more lines than a
/// table of limits::kMaxTableRows rows can have.
std::vector<std::string_view> split_lines(std::string_view text, std::string_view source) {
  if (text.size() > limits::kMaxTextFileBytes)
    too_large(source, std::to_string(text.size()) + " bytes", limits::kMaxTextFileBytes);
  // Headers, keywords and comments: a few hundred lines at most in real files.
  const std::size_t max_lines = limits::kMaxTableRows + 10000;
  std::size_t n_lines = 0;
  for (char c : text) n_lines += c == '\n' || c == '\r';
  if (n_lines > 2 * max_lines) too_large(source, std::to_string(n_lines) + "+ lines", max_lines);
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF &&
      static_cast<unsigned char>(text[1]) == 0xBB && static_cast<unsigned char>(text[2]) == 0xBF)
    text.remove_prefix(3);
  std::vector<std::string_view> lines;
  size_t start = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || c == '\r') {
      lines.push_back(text.substr(start, i - start));
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      start = i + 1;
    }
  }
  if (start < text.size()) lines.push_back(text.substr(start));
  if (lines.size() > max_lines) too_large(source, std::to_string(lines.size()) + " lines", max_lines);
  return lines;
}

// Cells are built a run of characters at a time, not a character at a time (issue 13: with
// Emscripten's JavaScript exceptions, each std::string::push_back was a call through an invoke_*
// trampoline; the wasm build now uses the engine's exceptions, and runs are cheaper anyway).
std::vector<std::string> split_delimited(std::string_view line, char delim) {
  std::vector<std::string> cells;
  cells.reserve(1 + static_cast<size_t>(std::count(line.begin(), line.end(), delim)));
  std::string cur;  // a cell with quotes in it, unquoted so far
  bool quoted = false;
  const size_t n = line.size();
  size_t i = 0;
  for (;;) {
    size_t j = i;  // end of the run of plain characters from i
    if (quoted)
      while (j < n && line[j] != '"') ++j;
    else
      while (j < n && line[j] != '"' && line[j] != delim) ++j;
    if (!quoted && cur.empty() && (j == n || line[j] == delim)) {  // a cell without quotes
      cells.push_back(trim(line.substr(i, j - i)));
      if (j == n) return cells;
      i = j + 1;
      continue;
    }
    cur.append(line.data() + i, j - i);
    if (j == n) break;
    if (quoted) {  // line[j] is a quote: "" is one quote, else the quoted part ends
      if (j + 1 < n && line[j + 1] == '"') {
        cur.push_back('"');
        i = j + 2;
      } else {
        quoted = false;
        i = j + 1;
      }
    } else if (line[j] == '"') {
      quoted = true;
      i = j + 1;
    } else {  // the delimiter
      cells.push_back(trim(cur));
      cur.clear();
      i = j + 1;
    }
  }
  cells.push_back(trim(cur));
  return cells;
}

/// Whitespace-separated tokens; "double quoted" tokens may hold spaces.
std::vector<std::string> split_ws(const std::string& line) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i >= line.size()) break;
    if (line[i] == '"') {
      const size_t end = line.find('"', i + 1);
      if (end == std::string::npos) {
        out.push_back(line.substr(i + 1));
        break;
      }
      out.push_back(line.substr(i + 1, end - i - 1));
      i = end + 1;
    } else {
      size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      out.push_back(line.substr(i, j - i));
      i = j;
    }
  }
  return out;
}

bool is_blank(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

/// A comment line: '#' after any leading white space (no copy of the line).
bool is_comment(std::string_view s) {
  size_t a = 0;
  while (a < s.size() && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  return a < s.size() && s[a] == '#';
}

/// Wavelength encoded in a column name ("380", "nm380", "SPECTRAL_380", "SPEC_380",
/// "SPECTRAL_NM380", "380nm", "R380"?) -> value, or NaN if the name is not a wavelength.
double wavelength_from_name(const std::string& name) {
  std::string s = lower(name);
  for (const char* prefix : {"spectral_nm_", "spectral_nm", "spectral_", "spec_", "nm_", "nm"}) {
    const std::string p(prefix);
    if (s.compare(0, p.size(), p) == 0) {
      s = s.substr(p.size());
      break;
    }
  }
  if (s.size() > 2 && s.compare(s.size() - 2, 2, "nm") == 0) s = s.substr(0, s.size() - 2);
  if (s.empty()) return std::nan("");
  char* end = nullptr;
  const double v = tristim::parse_double(s.c_str(), &end);
  if (*end != '\0' || !std::isfinite(v) || v < 200 || v > 2000) return std::nan("");
  return v;
}

/// Finds the value columns of a header; fills a PatchTable from cell rows.
struct ColumnMap {
  int id = -1, index = -1;
  std::vector<int> id_candidates;  // id-like columns in order of preference
  int XYZ[3] = {-1, -1, -1}, Lab[3] = {-1, -1, -1}, RGB[3] = {-1, -1, -1};
  std::vector<int> spectral;
  std::vector<double> wavelengths;
};

int find_col(const std::vector<std::string>& header, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (size_t i = 0; i < header.size(); ++i)
      if (lower(header[i]) == lower(n)) return static_cast<int>(i);
  return -1;
}
int find_exact(const std::vector<std::string>& header, const char* name) {
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

void require_triplet(const int (&c)[3], const char* what, const std::vector<std::string>& header,
                     std::string_view source, int line) {
  const int present = (c[0] >= 0) + (c[1] >= 0) + (c[2] >= 0);
  if (present == 0 || present == 3) return;
  static const char* axis[3] = {"first", "second", "third"};
  for (int k = 0; k < 3; ++k)
    if (c[k] < 0)
      throw Error(ErrorCode::MissingColumn, where(source, line) + ": " + what + " columns incomplete (the " +
                                                axis[k] + " component is missing; header has " +
                                                std::to_string(header.size()) + " columns)");
}

ColumnMap map_columns(const std::vector<std::string>& header, std::string_view source, int line) {
  ColumnMap m;
  for (const char* n : {"patch", "id", "sample_id", "sampleid", "sample_name", "samplename", "sample_loc", "name", "sample",
                        "patch_id", "patch_name", "location"}) {
    const int c = find_col(header, {n});
    if (c >= 0 && std::find(m.id_candidates.begin(), m.id_candidates.end(), c) == m.id_candidates.end())
      m.id_candidates.push_back(c);
  }
  m.id = m.id_candidates.empty() ? -1 : m.id_candidates.front();
  m.index = find_col(header, {"index", "#", "idx", "no", "number"});
  // X_ref, Y_ref, Z_ref: the reference columns of the engine's own per-patch CSV (patch_csv), so
  // that file reads back as a reference.
  m.XYZ[0] = find_col(header, {"xyz_x", "x", "cie_x", "x_ref"});
  m.XYZ[1] = find_col(header, {"xyz_y", "y", "cie_y", "y_ref"});
  m.XYZ[2] = find_col(header, {"xyz_z", "z", "cie_z", "z_ref"});
  m.Lab[0] = find_col(header, {"lab_l", "l*", "l", "cie_l"});
  m.Lab[1] = find_col(header, {"lab_a", "a*", "a", "cie_a"});
  m.RGB[0] = find_col(header, {"rgb_r", "r", "red"});
  m.RGB[1] = find_col(header, {"rgb_g", "g", "green"});
  // "b": Lab b* or RGB blue. Explicit names first, then the lone letter by context.
  m.Lab[2] = find_col(header, {"lab_b", "b*", "cie_b"});
  m.RGB[2] = find_col(header, {"rgb_b", "blue"});
  const bool lab_context = m.Lab[0] >= 0 && m.Lab[1] >= 0;
  const bool rgb_context = m.RGB[0] >= 0 && m.RGB[1] >= 0;
  if (m.Lab[2] < 0 && lab_context) {
    const int exact = find_exact(header, "b");
    m.Lab[2] = exact >= 0 ? exact : (rgb_context ? -1 : find_col(header, {"b"}));
  }
  if (m.RGB[2] < 0 && rgb_context) {
    const int exact = find_exact(header, "B");
    int any = exact >= 0 ? exact : find_col(header, {"b"});
    if (any == m.Lab[2]) any = -1;
    m.RGB[2] = any;
  }
  for (size_t i = 0; i < header.size(); ++i) {
    const int ii = static_cast<int>(i);
    if (ii == m.index || std::find(m.id_candidates.begin(), m.id_candidates.end(), ii) != m.id_candidates.end()) continue;
    const double wl = wavelength_from_name(header[i]);
    if (std::isfinite(wl)) {
      m.spectral.push_back(ii);
      m.wavelengths.push_back(wl);
    }
  }
  require_triplet(m.XYZ, "XYZ", header, source, line);
  require_triplet(m.Lab, "Lab", header, source, line);
  require_triplet(m.RGB, "RGB", header, source, line);
  for (size_t k = 1; k < m.wavelengths.size(); ++k)
    if (!(m.wavelengths[k] > m.wavelengths[k - 1]))
      throw Error(ErrorCode::NonMonotonic, where(source, line) + ": spectral columns not strictly increasing (" +
                                               header[m.spectral[k - 1]] + " then " + header[m.spectral[k]] + ")");
  if (m.XYZ[0] < 0 && m.Lab[0] < 0 && m.RGB[0] < 0 && m.spectral.empty())
    throw Error(ErrorCode::MissingColumn,
                where(source, line) + ": no XYZ, Lab, RGB or spectral columns (e.g. X,Y,Z or L,a,b or R,G,B)");
  return m;
}

PatchTable fill_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                      const std::vector<int>& lines, std::string_view source, int header_line) {
  ColumnMap m = map_columns(header, source, header_line);
  if (rows.empty()) throw Error(ErrorCode::EmptyFile, std::string(source.empty() ? "input" : source) + ": no data rows");
  // Several id columns (i1Profiler: SampleID 1..N and SAMPLE_NAME A1..; Argyll .ti2/.ti3: SAMPLE_ID
  // 1..N and SAMPLE_LOC A01..): prefer the first whose values are not all plain numbers, so the ids
  // pair with chart patch ids.
  if (m.id_candidates.size() > 1) {
    for (int c : m.id_candidates) {
      const bool numeric = std::all_of(rows.begin(), rows.end(), [&](const std::vector<std::string>& r) {
        return !r[c].empty() && std::all_of(r[c].begin(), r[c].end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); });
      });
      if (!numeric) {
        m.id = c;
        break;
      }
    }
  }
  PatchTable t;
  t.has_XYZ = m.XYZ[0] >= 0;
  t.has_Lab = m.Lab[0] >= 0;
  t.has_RGB = m.RGB[0] >= 0;
  t.has_spectra = !m.spectral.empty();
  if (t.has_spectra) t.spectra.wavelengths = m.wavelengths;
  std::map<std::string, int> seen;
  for (size_t r = 0; r < rows.size(); ++r) {
    const auto& row = rows[r];
    const int line = lines[r];
    // The key pairs the row with other data; the label is the id as written, for outputs.
    const int id_col = m.id >= 0 ? m.id : m.index;
    std::string label = id_col >= 0 ? trim(row[id_col]) : std::to_string(r + 1);
    std::string id = id_col >= 0 ? normalise_patch_id(label) : label;
    if (id.empty())
      throw Error(ErrorCode::ParseError, where(source, line) + ": empty patch id in column '" + header[id_col] + "'");
    auto ins = seen.emplace(id, static_cast<int>(r));
    if (!ins.second) {
      const std::string& first = t.labels[static_cast<size_t>(ins.first->second)];
      throw Error(ErrorCode::DuplicateId, where(source, line) + ": duplicate patch id '" + label + "' (first on line " +
                                              std::to_string(lines[static_cast<size_t>(ins.first->second)]) +
                                              (first == label ? "" : ", as '" + first + "'") + ")");
    }
    t.ids.push_back(id);
    t.labels.push_back(std::move(label));
    auto triplet = [&](const int (&c)[3], std::vector<Vec3>& out) {
      if (c[0] < 0) return;
      Vec3 v;
      for (int k = 0; k < 3; ++k) v[k] = parse_cell(row[c[k]], source, line, header[c[k]]);
      out.push_back(v);
    };
    triplet(m.XYZ, t.XYZ);
    triplet(m.Lab, t.Lab);
    triplet(m.RGB, t.RGB);
    if (t.has_spectra) {
      std::vector<double> s(m.spectral.size());
      for (size_t k = 0; k < m.spectral.size(); ++k) s[k] = parse_cell(row[m.spectral[k]], source, line, header[m.spectral[k]]);
      t.spectra.values.push_back(std::move(s));
      t.spectra.names.push_back(id);
    }
  }
  return t;
}

}  // namespace

std::string normalise_patch_id(std::string_view raw) {
  std::string s;
  for (char c : raw)
    if (!std::isspace(static_cast<unsigned char>(c))) s.push_back(c);
  // letters+digits groups, e.g. A01, R01C02: strip leading zeros from each digit group.
  bool pattern = !s.empty() && std::isalpha(static_cast<unsigned char>(s[0]));
  for (char c : s) pattern = pattern && std::isalnum(static_cast<unsigned char>(c));
  if (!pattern) return trim(raw);
  bool any_digit = std::any_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  if (!any_digit) return trim(raw);
  // Only short letter groups (chart ids such as A1, AA12, R1C2) are upper-cased and stripped.
  size_t letters = 0;
  for (char c : s) letters += std::isalpha(static_cast<unsigned char>(c)) ? 1 : 0;
  if (letters > 4) return trim(raw);
  std::string out;
  size_t i = 0;
  while (i < s.size()) {
    if (std::isdigit(static_cast<unsigned char>(s[i]))) {
      size_t j = i;
      while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
      size_t k = i;
      while (k + 1 < j && s[k] == '0') ++k;
      out.append(s, k, j - k);
      i = j;
    } else {
      out.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(s[i]))));
      ++i;
    }
  }
  return out;
}

int TextTable::find(std::initializer_list<const char*> names) const { return find_col(header, names); }

TextTable parse_delimited(std::string_view text, std::string_view source) {
  TextTable t;
  t.source = std::string(source);
  const auto lines = split_lines(text, source);
  size_t i = 0;
  while (i < lines.size() && (is_blank(lines[i]) || is_comment(lines[i]))) ++i;
  if (i >= lines.size()) throw Error(ErrorCode::EmptyFile, std::string(source.empty() ? "input" : source) + ": empty file");
  const std::string_view head = lines[i];
  const size_t commas = std::count(head.begin(), head.end(), ','), semis = std::count(head.begin(), head.end(), ';'),
               tabs = std::count(head.begin(), head.end(), '\t');
  const char delim = (tabs > commas && tabs > semis) ? '\t' : (semis > commas ? ';' : ',');
  t.header = split_delimited(head, delim);
  if (t.header.size() > limits::kMaxTableColumns)
    too_large(source, std::to_string(t.header.size()) + " columns", limits::kMaxTableColumns);
  t.header_line = static_cast<int>(i) + 1;
  // A trailing delimiter on every line (spreadsheet exports) is an empty last column: dropped.
  const bool trailing = t.header.size() > 1 && t.header.back().empty();
  if (trailing) t.header.pop_back();
  for (size_t k = 0; k < t.header.size(); ++k)
    if (t.header[k].empty() && t.header.size() > 1)
      throw Error(ErrorCode::ParseError, where(source, t.header_line) + ": column " + std::to_string(k + 1) + " has no name");
  for (++i; i < lines.size(); ++i) {
    if (is_blank(lines[i]) || is_comment(lines[i])) continue;
    auto cells = split_delimited(lines[i], delim);
    if (trailing && cells.size() == t.header.size() + 1 && cells.back().empty()) cells.pop_back();
    if (cells.size() != t.header.size())
      throw Error(ErrorCode::RowLength, where(source, static_cast<int>(i) + 1) + ": " + std::to_string(cells.size()) +
                                            " values, the header has " + std::to_string(t.header.size()));
    if (t.rows.size() >= limits::kMaxTableRows) too_large(source, "more than " + std::to_string(t.rows.size()) + " rows", limits::kMaxTableRows);
    t.rows.push_back(std::move(cells));
    t.lines.push_back(static_cast<int>(i) + 1);
  }
  return t;
}

double parse_cell(const std::string& cell, std::string_view source, int line, std::string_view column) {
  // Cells from split_delimited are trimmed already: copy only one with white space around it.
  const bool padded = !cell.empty() && (std::isspace(static_cast<unsigned char>(cell.front())) ||
                                        std::isspace(static_cast<unsigned char>(cell.back())));
  const std::string trimmed = padded ? trim(cell) : std::string();
  const std::string& s = padded ? trimmed : cell;
  // Only built for a message (a cell is parsed once per number of a table: no allocation on success).
  auto at = [&] { return where(source, line) + ", column '" + std::string(column) + "'"; };
  if (s.empty()) throw Error(ErrorCode::NonNumeric, at() + ": empty cell where a number is needed");
  char* end = nullptr;
  double v = tristim::parse_double(s.c_str(), &end);
  bool whole = end != s.c_str() && *end == '\0';  // the cell is one number
  if (!whole && std::count(s.begin(), s.end(), ',') == 1 && s.find('.') == std::string::npos) {
    std::string dot = s;  // decimal comma ("0,123": ';'-separated CSV or CGATS from a European locale)
    dot[dot.find(',')] = '.';
    char* dot_end = nullptr;  // points into `dot`: never used after this block (fuzz_patch_file found that)
    const double d = tristim::parse_double(dot.c_str(), &dot_end);
    if (dot_end != dot.c_str() && *dot_end == '\0') {
      v = d;
      whole = true;
    }
  }
  if (!whole) throw Error(ErrorCode::NonNumeric, at() + ": '" + s + "' is not a number");
  if (!std::isfinite(v)) throw Error(ErrorCode::NonFinite, at() + ": '" + s + "' is not finite");
  return v;
}

SpectralData read_spectral_csv(std::string_view text, std::string_view source) {
  const TextTable t = parse_delimited(text, source);
  if (t.header.size() < 2)
    throw Error(ErrorCode::MissingColumn,
                where(source, t.header_line) + ": a spectral CSV needs a wavelength column and at least one data column");
  if (t.rows.empty()) throw Error(ErrorCode::EmptyFile, std::string(source.empty() ? "input" : source) + ": no data rows");
  SpectralData d;
  d.names.assign(t.header.begin() + 1, t.header.end());
  d.values.assign(d.names.size(), {});
  d.wavelengths.reserve(t.rows.size());
  for (auto& column : d.values) column.reserve(t.rows.size());
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const double wl = parse_cell(t.rows[r][0], source, t.lines[r], t.header[0]);
    if (!d.wavelengths.empty() && !(wl > d.wavelengths.back()))
      throw Error(ErrorCode::NonMonotonic, where(source, t.lines[r]) + ": wavelength " + t.rows[r][0] +
                                               " does not increase (previous " + t.rows[r - 1][0] + ")");
    d.wavelengths.push_back(wl);
    for (size_t k = 1; k < t.header.size(); ++k) d.values[k - 1].push_back(parse_cell(t.rows[r][k], source, t.lines[r], t.header[k]));
  }
  return d;
}

SpectralData read_illuminant_csv(std::string_view text, std::string_view source) {
  SpectralData d = read_spectral_csv(text, source);
  const std::string name(source.empty() ? "input" : source);
  if (d.values.size() != 1) {
    std::string cols;
    for (const auto& n : d.names) cols += (cols.empty() ? "" : ", ") + n;
    throw Error(ErrorCode::InvalidArgument,
                name + ": an illuminant file has the wavelength and one value column; this one has " +
                    std::to_string(d.values.size()) + " (" + cols + ")");
  }
  double peak = 0;
  for (size_t i = 0; i < d.values[0].size(); ++i) {
    const double v = d.values[0][i];
    if (v < 0) {
      std::ostringstream ss;
      ss << name << ": the illuminant's power at " << d.wavelengths[i] << " nm is negative (" << v << ")";
      throw Error(ErrorCode::NegativeValue, ss.str());
    }
    peak = std::max(peak, v);
  }
  if (!(peak > 0)) throw Error(ErrorCode::NoUsableData, name + ": the illuminant's power is zero at every wavelength");
  return d;
}

SpectralData read_reflectance_file(std::string_view text, std::string_view source) {
  const PatchTable t = read_patch_file(text, source);
  if (!t.has_spectra)
    throw Error(ErrorCode::MissingColumn, std::string(source.empty() ? "input" : source) +
                                              ": no spectral columns (first column wavelength, or 380,390,... columns)");
  SpectralData s = t.spectra;
  reflectance_to_fraction(s);
  return s;
}

PatchTable read_patch_csv(std::string_view text, std::string_view source) {
  const TextTable t = parse_delimited(text, source);
  PatchTable p = fill_table(t.header, t.rows, t.lines, source, t.header_line);
  p.format = "csv";
  return p;
}

PatchTable read_cgats(std::string_view text, std::string_view source) {
  const auto lines = split_lines(text, source);
  size_t i = 0;
  while (i < lines.size() && is_blank(lines[i])) ++i;
  if (i >= lines.size()) throw Error(ErrorCode::EmptyFile, std::string(source.empty() ? "input" : source) + ": empty file");
  PatchTable out;
  std::vector<std::string> fields;
  int format_line = 0;
  long declared_fields = -1, declared_sets = -1;  // declared_fields: informative only
  std::vector<std::vector<std::string>> rows;
  std::vector<int> row_lines;
  bool in_format = false, in_data = false, done = false;
  int data_line = 0;
  for (; i < lines.size() && !done; ++i) {
    const int ln = static_cast<int>(i) + 1;
    const std::string s = trim(lines[i]);
    if (s.empty() || s[0] == '#') continue;
    if (in_format) {
      if (s.rfind("END_DATA_FORMAT", 0) == 0) {
        in_format = false;
        continue;
      }
      for (auto& f : split_ws(s)) fields.push_back(f);
      if (fields.size() > limits::kMaxTableColumns)
        too_large(source, std::to_string(fields.size()) + " fields", limits::kMaxTableColumns);
      continue;
    }
    if (in_data) {
      if (s.rfind("END_DATA", 0) == 0) {
        in_data = false;
        if (!rows.empty()) done = true;  // first table with data wins
        continue;
      }
      auto cells = split_ws(s);
      if (cells.size() != fields.size())
        throw Error(ErrorCode::RowLength, where(source, ln) + ": " + std::to_string(cells.size()) + " values, BEGIN_DATA_FORMAT has " +
                                              std::to_string(fields.size()) + " fields");
      if (rows.size() >= limits::kMaxTableRows) too_large(source, "more than " + std::to_string(rows.size()) + " rows", limits::kMaxTableRows);
      rows.push_back(std::move(cells));
      row_lines.push_back(ln);
      continue;
    }
    if (s.rfind("BEGIN_DATA_FORMAT", 0) == 0) {
      fields.clear();
      rows.clear();
      row_lines.clear();
      in_format = true;
      format_line = ln;
      continue;
    }
    if (s.rfind("BEGIN_DATA", 0) == 0) {
      if (fields.empty())
        throw Error(ErrorCode::ParseError, where(source, ln) + ": BEGIN_DATA before any BEGIN_DATA_FORMAT");
      // NUMBER_OF_FIELDS is not checked against the format: real files (e.g. dcamprof's X-Rite
      // .cie) get it wrong; every row is checked against the format instead.
      in_data = true;
      data_line = ln;
      continue;
    }
    // keyword line: KEY value (value possibly quoted)
    auto toks = split_ws(s);
    if (toks.empty()) continue;
    if (toks[0] == "KEYWORD") continue;
    const std::string value = toks.size() > 1 ? toks[1] : "";
    if (toks[0] == "NUMBER_OF_FIELDS" || toks[0] == "NUMBER_OF_SETS") {
      char* end = nullptr;
      const long v = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || v < 0)
        throw Error(ErrorCode::ParseError, where(source, ln) + ": " + toks[0] + " needs a count, got '" + value + "'");
      (toks[0] == "NUMBER_OF_FIELDS" ? declared_fields : declared_sets) = v;
      (void)declared_fields;
      continue;
    }
    if (out.keywords.count(toks[0]) == 0) out.keywords[toks[0]] = value;
  }
  if (in_format) throw Error(ErrorCode::ParseError, where(source, format_line) + ": BEGIN_DATA_FORMAT without END_DATA_FORMAT");
  if (in_data) throw Error(ErrorCode::ParseError, where(source, data_line) + ": BEGIN_DATA without END_DATA");
  if (fields.empty())
    throw Error(ErrorCode::ParseError, std::string(source.empty() ? "input" : source) + ": no BEGIN_DATA_FORMAT block (not a CGATS file?)");
  if (rows.empty()) throw Error(ErrorCode::EmptyFile, std::string(source.empty() ? "input" : source) + ": the data block has no rows");
  if (declared_sets >= 0 && declared_sets != static_cast<long>(rows.size()))
    throw Error(ErrorCode::RowLength, where(source, data_line) + ": NUMBER_OF_SETS " + std::to_string(declared_sets) + " but " +
                                          std::to_string(rows.size()) + " rows follow");
  PatchTable t = fill_table(fields, rows, row_lines, source, format_line);
  t.keywords = std::move(out.keywords);
  t.format = "cgats";
  if (t.has_spectra) {
    auto it = t.keywords.find("SPECTRAL_NORM");
    double norm = 0;
    if (it != t.keywords.end()) norm = tristim::parse_double(it->second.c_str(), nullptr);
    if (norm > 0 && norm != 1.0) {
      for (auto& col : t.spectra.values)
        for (auto& v : col) v /= norm;
    } else if (norm <= 0) {
      reflectance_to_fraction(t.spectra);
    }
  }
  return t;
}

PatchTable read_patch_file(std::string_view text, std::string_view file_name) {
  const std::string name = lower(file_name);
  const auto dot = name.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : name.substr(dot + 1);
  bool cgats = text.find("BEGIN_DATA_FORMAT") != std::string_view::npos;
  if (!cgats && (ext == "ti1" || ext == "ti2" || ext == "ti3" || ext == "cie" || ext == "cht" || ext == "cgats" || ext == "it8"))
    cgats = true;
  if (cgats) return read_cgats(text, file_name);
  const TextTable t = parse_delimited(text, file_name);
  const std::string first = lower(t.header.empty() ? "" : t.header[0]);
  const bool spectral = first == "wavelength" || first == "wavelength_nm" || first == "wavelengths" || first == "nm" ||
                        first == "lambda" || first == "wl" || first == "wavelength (nm)" || first == "wavelength(nm)" ||
                        first == "λ";
  if (!spectral) {
    PatchTable p = fill_table(t.header, t.rows, t.lines, file_name, t.header_line);
    p.format = "csv";
    return p;
  }
  PatchTable p;
  p.format = "csv-spectral";
  p.spectra = read_spectral_csv(text, file_name);
  p.has_spectra = true;
  std::map<std::string, size_t> seen;
  for (size_t k = 0; k < p.spectra.names.size(); ++k) {
    std::string label = trim(p.spectra.names[k]);
    std::string id = normalise_patch_id(label);
    if (id.empty())
      throw Error(ErrorCode::ParseError, where(file_name, t.header_line) + ": empty column name " + std::to_string(k + 2));
    const auto ins = seen.emplace(id, k);
    if (!ins.second) {
      const std::string& first = p.labels[ins.first->second];
      throw Error(ErrorCode::DuplicateId, where(file_name, t.header_line) + ": duplicate patch id '" + label + "' in the header" +
                                              (first == label ? "" : " (the same patch as '" + first + "')"));
    }
    p.spectra.names[k] = id;
    p.ids.push_back(id);
    p.labels.push_back(std::move(label));
  }
  return p;
}

std::vector<std::string> patch_labels(const PatchTable& table, const std::vector<std::string>& ids) {
  std::map<std::string, const std::string*> label_of;
  for (size_t i = 0; i < table.ids.size() && i < table.labels.size(); ++i) label_of.emplace(table.ids[i], &table.labels[i]);
  std::vector<std::string> out;
  out.reserve(ids.size());
  for (const auto& id : ids) {
    const auto it = label_of.find(normalise_patch_id(id));
    out.push_back(it == label_of.end() ? id : *it->second);
  }
  return out;
}

}  // namespace tristim

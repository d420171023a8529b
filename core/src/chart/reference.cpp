// Built-in reference charts: spectra and X-Rite Lab (core/data/charts, origins in SOURCES.md).
#include <algorithm>
#include <map>
#include <mutex>
#include <set>

#include <Eigen/LU>

#include "tristim/chart/layout.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/data.hpp"
#include "tristim/error.hpp"

namespace tristim {

namespace {

// A built-in chart's data files. Its grid (rows × columns, patch ids) is its layout's
// (chart/layout.hpp: chart_layout), the one place a chart's geometry is written.
struct ChartFiles {
  const char* id;
  const char* name;
  const char* source;  // where the spectra and Lab come from (short)
  const char* spectra;
  const char* lab;
};

const std::vector<ChartFiles>& chart_table() {
  static const std::vector<ChartFiles> t = {
      {"cc24", "ColorChecker Classic (X-Rite, Nov 2014 and newer)",
       "X-Rite reference spectra (380-730 nm, 10 nm) and Lab D50",
       "charts/colorchecker24_after_nov2014_reflectance_380-730_10nm.csv",
       "charts/colorchecker24_xrite_after_nov2014_Lab_D50.csv"},
      {"cc24-2005", "ColorChecker Classic (X-Rite/GretagMacbeth, before Nov 2014)",
       "X-Rite reference spectra (380-730 nm, 5 nm) and Lab D50",
       "charts/colorchecker24_before_nov2014_reflectance_380-730_5nm.csv",
       "charts/colorchecker24_xrite_before_nov2014_Lab_D50.csv"},
      {"sg140", "ColorChecker Digital SG (X-Rite, Nov 2014 and newer)",
       "X-Rite reference spectra (380-730 nm, 10 nm) and Lab D50",
       "charts/colorcheckerSG_after_nov2014_reflectance_380-730_10nm.csv",
       "charts/colorcheckerSG140_xrite_after_nov2014_Lab_D50.csv"},
      {"sg140-2005", "ColorChecker Digital SG (X-Rite, before Nov 2014)",
       "X-Rite reference spectra (380-730 nm, 10 nm) and Lab D50",
       "charts/colorcheckerSG_before_nov2014_reflectance_380-730_10nm.csv",
       "charts/colorcheckerSG140_xrite_before_nov2014_Lab_D50.csv"},
      {"passport", "ColorChecker Passport, classic 24 side (X-Rite, Nov 2014 and newer)",
       "ColorChecker Classic (Nov 2014 and newer) reference spectra and Lab D50: same colorants",
       "charts/colorchecker24_after_nov2014_reflectance_380-730_10nm.csv",
       "charts/colorchecker24_xrite_after_nov2014_Lab_D50.csv"},
  };
  return t;
}

const ChartFiles& find_chart(std::string_view id) {
  for (const auto& c : chart_table())
    if (c.id == id) return c;
  std::string known;
  for (const auto& c : chart_table()) known += (known.empty() ? "" : ", ") + std::string(c.id);
  throw Error(ErrorCode::UnknownId, "unknown chart '" + std::string(id) + "' (built-in: " + known + ")");
}

}  // namespace

std::vector<ChartInfo> list_charts() {
  std::vector<ChartInfo> out;
  for (const auto& c : chart_table()) {
    LayoutOptions o;
    o.chart = c.id;
    const ChartLayout layout = chart_layout(o);
    out.push_back({c.id, c.name, static_cast<int>(layout.patches.size()), layout.rows, layout.columns, c.source});
  }
  return out;
}

SpectralData chart_reflectances(std::string_view chart_id) {
  const ChartFiles& c = find_chart(chart_id);
  static std::mutex mutex;
  static std::map<std::string, SpectralData> cache;  // parsed once per file
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(c.spectra);
  if (it == cache.end())
    it = cache.emplace(c.spectra, read_patch_file(builtin_file(c.spectra), c.spectra).spectra).first;  // A01 -> A1
  return it->second;
}

Mat3 display_matrix(const Vec3& white) {
  // Bradford maps `white` onto the sRGB white (D65 from its xy, Y = 100); /100 brings it to
  // linear sRGB (1, 1, 1) exactly.
  static const Mat3 to_XYZ = sRGB_to_XYZ_matrix();
  static const Mat3 from_XYZ = to_XYZ.inverse();
  const Mat3 M = chromatic_adaptation_matrix(white, to_XYZ * Vec3(100, 100, 100), ChromaticAdaptation::Bradford);
  return from_XYZ * M / 100.0;
}

Vec3 display_sRGB(const Vec3& XYZ, const Vec3& white) {
  return sRGB_encode(display_matrix(white) * XYZ);
}

ReferenceChart reference_from_spectra(const SpectralData& reflectances, const SpectralData& illuminant,
                                      Observer observer) {
  ReferenceChart r;
  r.illuminant_id = illuminant.names.empty() ? "" : illuminant.names[0];
  r.observer = observer;
  r.ids = reflectances.names;
  r.labels = reflectances.names;
  r.XYZ = reflectances_to_XYZ(reflectances, illuminant, observer, &r.white);  // the white too (one weighting)
  const Mat3 display = display_matrix(r.white);  // once, not per patch (display_sRGB, the same floats)
  for (const auto& xyz : r.XYZ) {
    r.Lab.push_back(XYZ_to_Lab(xyz, r.white));
    r.sRGB.push_back(sRGB_encode(display * xyz));
  }
  return r;
}

ReferenceChart reference_chart(std::string_view chart_id, std::string_view illuminant_id, Observer observer) {
  ReferenceChart r = reference_from_spectra(chart_reflectances(chart_id), illuminant_spd(illuminant_id), observer);
  r.chart_id = std::string(chart_id);
  return r;
}

ReferenceChart reference_from_table(const PatchTable& table, const SpectralData& illuminant, Observer observer) {
  if (table.has_spectra) {
    SpectralData s = table.spectra;
    reflectance_to_fraction(s);
    ReferenceChart r = reference_from_spectra(s, illuminant, observer);
    if (table.labels.size() == r.ids.size()) r.labels = table.labels;  // the file's own spelling
    return r;
  }
  if (!table.has_XYZ && !table.has_Lab)
    throw Error(ErrorCode::MissingColumn, "the file has no spectral, XYZ or Lab columns to use as a reference");
  ReferenceChart r;
  r.illuminant_id = illuminant.names.empty() ? "" : illuminant.names[0];
  r.observer = observer;
  r.ids = table.ids;
  r.labels = table.labels.size() == table.ids.size() ? table.labels : table.ids;
  r.white = illuminant_white_XYZ(illuminant, observer);
  // XYZ tables on the 0..1 scale (every Y <= 1.5) are brought to the Y = 100 scale of the white.
  double max_Y = 0;
  if (table.has_XYZ)
    for (const auto& v : table.XYZ) max_Y = std::max(max_Y, v[1]);
  const double scale = table.has_XYZ && max_Y <= 1.5 ? 100.0 : 1.0;
  for (size_t i = 0; i < table.ids.size(); ++i) {
    const Vec3 XYZ = table.has_XYZ ? Vec3(table.XYZ[i] * scale) : Lab_to_XYZ(table.Lab[i], r.white);
    r.XYZ.push_back(XYZ);
    r.Lab.push_back(table.has_Lab ? table.Lab[i] : XYZ_to_Lab(XYZ, r.white));
    r.sRGB.push_back(display_sRGB(XYZ, r.white));
  }
  return r;
}

PatchPairs pair_by_id(const std::vector<std::string>& reference_ids, const std::vector<Vec3>& reference,
                      const std::vector<std::string>& measured_ids, const std::vector<Vec3>& measured) {
  if (reference_ids.size() != reference.size() || measured_ids.size() != measured.size())
    throw Error(ErrorCode::PatchMismatch, "ids and rows differ in number");
  // The measurement's order (see the header): a user's patches in the order they measured them.
  // It is the order of a chart sample (layout order), so the page, `tristim fit --recipe` and a
  // profile's training digest see the same rows whether the RGB came from an image or a file.
  std::map<std::string, size_t> row_of;  // normalised reference id -> its first row
  for (size_t i = 0; i < reference_ids.size(); ++i) row_of.emplace(normalise_patch_id(reference_ids[i]), i);
  std::set<std::string> in_measured;
  PatchPairs p;
  for (size_t i = 0; i < measured_ids.size(); ++i) {
    const std::string id = normalise_patch_id(measured_ids[i]);
    in_measured.insert(id);
    const auto it = row_of.find(id);
    if (it == row_of.end()) {
      p.missing_in_reference.push_back(id);
      continue;
    }
    p.ids.push_back(id);
    p.measured.push_back(measured[i]);
    p.reference.push_back(reference[it->second]);
    p.measured_rows.push_back(static_cast<int>(i));
    p.reference_rows.push_back(static_cast<int>(it->second));
  }
  for (const auto& rid : reference_ids)
    if (!in_measured.count(normalise_patch_id(rid))) p.missing_in_measured.push_back(normalise_patch_id(rid));
  if (p.ids.empty())
    throw Error(ErrorCode::PatchMismatch, "no patch id is shared by the measurement and the reference (e.g. reference '" +
                                              (reference_ids.empty() ? std::string() : reference_ids[0]) + "', measured '" +
                                              (measured_ids.empty() ? std::string() : measured_ids[0]) + "')");
  return p;
}

PublishedReference published_reference_Lab(std::string_view chart_id) {
  const ChartFiles& c = find_chart(chart_id);
  const TextTable t = parse_delimited(builtin_file(c.lab), c.lab);
  PublishedReference p;
  p.chart_id = std::string(chart_id);
  p.source = "X-Rite (2016) CIELAB D50/2°, via colour-science";
  const int id_col = t.find({"patch"}), L = t.find({"l"}), a = t.find({"a"}), b = t.find({"b"});
  LayoutOptions o;
  o.chart = c.id;
  const ChartLayout layout = chart_layout(o);
  const bool cc24 = layout.patches.size() == 24;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    // The CC24 tables name patches ("dark skin" ...) in chart order (the layout's, row-major
    // A1..A6, B1..): use the order.
    const std::string id = cc24 && i < layout.patches.size() ? layout.patches[i].id : normalise_patch_id(t.rows[i][id_col]);
    p.ids.push_back(id);
    p.Lab.emplace_back(parse_cell(t.rows[i][L], c.lab, t.lines[i], "L"), parse_cell(t.rows[i][a], c.lab, t.lines[i], "a"),
                       parse_cell(t.rows[i][b], c.lab, t.lines[i], "b"));
  }
  return p;
}

}  // namespace tristim

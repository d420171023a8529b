// The lab's exercise 4: Abed, Berns & Masaoka (2013) Table IV with every training row of the
// paper, composed from surface/geometry_table (the simulated experiment and the five methods).
// Rules in tristim/lab/exercises.hpp.
#include <cmath>

#include "tristim/error.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/surface/geometry_table.hpp"

namespace tristim {

namespace {

/// 50 Munsell chips standing in for the paper's custom paint chart (every 25th of the 1269).
SpectralData custom_chart_spectra() {
  const SpectralData& m = munsell_reflectances();
  SpectralData s;
  s.wavelengths = m.wavelengths;
  s.linear = m.linear;
  for (size_t i = 0; i < m.size() && s.size() < 50; i += 25) {
    s.names.push_back(m.names[i]);
    s.values.push_back(m.values[i]);
  }
  return s;
}

/// Table IV of the paper: {ΔE_xyz mean, max, CIEDE2000 mean, max} per training row (Classic, SG,
/// Custom All, Custom-Matte, Custom-Glossy, Total) × method (scaler-offset, saunderson,
/// matrix-3x3, matrix-3x4, corrected-3x3).
constexpr double kPaper[6][5][4] = {
    {{0.0052, 0.0190, 2.4, 8.1}, {0.0051, 0.0188, 2.3, 8}, {0.0074, 0.0154, 2.5, 7.1}, {0.0111, 0.0150, 3.7, 7.3}, {0.0051, 0.0198, 2.4, 7.8}},
    {{0.0060, 0.0166, 2.4, 7}, {0.0058, 0.0189, 2.4, 8.3}, {0.0182, 0.0534, 3.3, 8}, {0.0474, 0.0559, 13, 26}, {0.0060, 0.0199, 2.7, 8.7}},
    {{0.0060, 0.0179, 2.7, 7.7}, {0.0068, 0.0182, 3, 8.1}, {0.0200, 0.0585, 3.2, 4.8}, {0.0420, 0.0493, 10.1, 19}, {0.0054, 0.0181, 2.6, 7.3}},
    {{0.0054, 0.0159, 2.5, 6.4}, {0.0057, 0.0156, 2.5, 6.6}, {0.0124, 0.0337, 2.7, 4.4}, {0.0255, 0.0316, 6.7, 13.1}, {0.0057, 0.0161, 2.6, 6.8}},
    {{0.0055, 0.0200, 2.6, 8.1}, {0.0052, 0.0200, 2.4, 7.8}, {0.0277, 0.0831, 3.9, 6.4}, {0.0586, 0.0705, 13.7, 24.4}, {0.0053, 0.0202, 2.5, 7.8}},
    {{0.0055, 0.0167, 2.5, 7.2}, {0.0068, 0.0181, 3, 8.2}, {0.0167, 0.0485, 2.9, 4.6}, {0.0378, 0.0441, 9.5, 18.4}, {0.0058, 0.0172, 2.6, 7.6}}};

}  // namespace

std::vector<Table4Row> lab_table4_exercise(const std::string& camera, const std::string& illuminant, double noise,
                                           std::uint64_t seed) {
  lab_option("table4.noise", noise);
  GeometryExperiment x = geometry_experiment_Abed2013(camera, illuminant, noise, seed);
  // x.training: Classic, SG, Glossy (SG spectra), Total (Classic + SG); the custom rows are ours.
  auto pair = [](const char* a) { return saunderson_preset(a).geometry; };
  const SpectralData custom = custom_chart_spectra();
  x.scene.camera.seed = seed + 10;
  const GeometryChart matte = simulate_geometry_chart("Custom-Matte", custom, pair("t3-matte-eye-one"), pair("t3-matte-diffuse"), x.scene);
  x.scene.camera.seed = seed + 11;
  const GeometryChart glossy = simulate_geometry_chart("Custom-Glossy", custom, pair("t3-glossy-eye-one"), pair("t3-glossy-diffuse"), x.scene);
  const GeometryChart all = combine_charts("Custom All", matte, glossy);
  const GeometryChart total = combine_charts("Total", combine_charts("Total", x.training[0], x.training[1]), all);
  const std::vector<GeometryChart> training{x.training[0], x.training[1], all, matte, glossy, total};
  const auto methods = geometry_table_methods();
  std::vector<Table4Row> out;
  for (const auto& c : geometry_table_Abed2013(training, x.test, x.options)) {
    Table4Row r;
    r.training = c.training;
    r.method = c.method;
    size_t t = 0, m = 0;
    while (t < training.size() && training[t].name != c.training) ++t;
    while (m < methods.size() && methods[m] != c.method) ++m;
    r.patches = t < training.size() ? static_cast<int>(training[t].ids.size()) : 0;
    r.ok = c.ok;
    r.error_code = c.error_code;
    if (c.ok) {
      r.dE_xyz_mean = c.dE_xyz.mean;
      r.dE_xyz_max = c.dE_xyz.max;
      r.dE00_mean = c.dE00.mean;
      r.dE00_max = c.dE00.max;
      r.mu = c.mu;
    }
    if (t < 6 && m < 5) {
      r.paper_dE_xyz_mean = kPaper[t][m][0];
      r.paper_dE_xyz_max = kPaper[t][m][1];
      r.paper_dE00_mean = kPaper[t][m][2];
      r.paper_dE00_max = kPaper[t][m][3];
    }
    out.push_back(r);
  }
  return out;
}

LabTable table4_table(const std::vector<Table4Row>& rows) {
  LabTable t{"lab-abed-table4",
             {"training", "method", "patches", "dE_xyz mean (Y_white = 1)", "dE_xyz max", "dE00 mean (CIEDE2000)", "dE00 max",
              "mu (corrected 3x3, eq 12)", "paper dE_xyz mean", "paper dE_xyz max", "paper dE00 mean", "paper dE00 max", "error"},
             {}};
  for (const auto& r : rows)
    t.rows.push_back({r.training, r.method, std::to_string(r.patches), r.ok ? lab_number(r.dE_xyz_mean) : "", r.ok ? lab_number(r.dE_xyz_max) : "",
                      r.ok ? lab_number(r.dE00_mean) : "", r.ok ? lab_number(r.dE00_max) : "", r.method == "corrected-3x3" && r.ok ? lab_number(r.mu) : "",
                      lab_number(r.paper_dE_xyz_mean), lab_number(r.paper_dE_xyz_max), lab_number(r.paper_dE00_mean), lab_number(r.paper_dE00_max), r.error_code});
  return t;
}

}  // namespace tristim

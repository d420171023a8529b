// Saunderson equations (Abed, Berns & Masaoka 2013, eqs 1-5, Appendices A-B) and literature presets.
#include "tristim/surface/saunderson.hpp"

#include <cmath>

#include "tristim/error.hpp"
#include "../table_lookup.hpp"

namespace tristim {

double saunderson_measured_Abed2013(double R_i, const SaundersonGeometry& g) {
  return (1 - g.k1) * (1 - g.k2) * R_i / (1 - g.k2 * R_i) + g.k_ins * g.k1;  // eq (1)
}

double saunderson_internal_Abed2013(double R_m, const SaundersonGeometry& g) {
  return (R_m - g.k_ins * g.k1) / ((1 - g.k1) * (1 - g.k2) + g.k2 * R_m - g.k_ins * g.k1 * g.k2);  // eq (2)
}

double saunderson_convert_Abed2013(double R_m, const SaundersonGeometry& m, const SaundersonGeometry& c) {
  // eq (3), derived from (2) then (1); see the errata in the header.
  const double num = (1 - c.k1) * (1 - c.k2) * (R_m - m.k_ins * m.k1);
  const double den = (1 - m.k1) * (1 - m.k2) - m.k_ins * m.k1 * m.k2 + m.k_ins * m.k1 * c.k2 + R_m * (m.k2 - c.k2);
  return num / den + c.k_ins * c.k1;
}

ThreeParameter three_parameter_Abed2013(const SaundersonGeometry& m, const SaundersonGeometry& c) {
  const double A = (1 - c.k1) * (1 - c.k2);                                        // eq (16)
  const double B = m.k2 - c.k2;                                                    // eq (17)
  const double C = (1 - m.k1) * (1 - m.k2) - m.k_ins * m.k1 * m.k2 + m.k_ins * m.k1 * c.k2;  // eq (18)
  const double D = c.k_ins * c.k1;                                                 // eq (19)
  const double E = (1 - c.k1) * (1 - c.k2) * m.k_ins * m.k1;                       // eq (20)
  const double scale = A + D * B;
  if (!(std::fabs(scale) > 1e-14))
    throw Error(ErrorCode::IllPosed,
                "Saunderson coefficients with (1 - k1c)(1 - k2c) + k_ins,c k1c (k2 - k2c) = 0: the capture "
                "geometry would give every patch the same reflectance (k1c or k2c = 1)");
  return {(D * C - E) / scale, B / scale, C / scale};  // eq (21)
}

ScalerOffset scaler_offset_Abed2013(const SaundersonGeometry& m, const SaundersonGeometry& c) {
  if (!(m.k1 < 1)) throw Error(ErrorCode::IllPosed, "scaler-offset from Saunderson coefficients needs k1 < 1");
  const double mu = (1 - c.k1) / (1 - m.k1);   // eq (25)
  return {mu, c.k_ins * c.k1 - mu * m.k_ins * m.k1};
}

namespace {

// k1: Abed 2013 p. 3 ("0.040 for parallel light and 0° incident angle and 0.092 for diffuse
// lighting geometries", refractive index ≈ 1.5, after Saunderson 1942 and Völz 1995).
// k2: Abed 2013 p. 3 ("recommended values for paint layers varies between 0.4 and 0.6"); 0.6 is
// the end the paper's own fits land near (Table III: 0.59-0.63).
// k_ins: the fraction of the specular reflection the detector receives — 1 when the instrument
// includes it (integrating sphere, SCI), 0 when it cannot reach the detector (SCE light trap,
// 45°:0° with the detector off the mirror direction).
std::vector<SaundersonPreset> build_presets() {
  const std::string k_text = "Abed, Berns & Masaoka 2013, p. 3: k1 = 0.040 parallel light, 0.092 diffuse light "
                             "(n ≈ 1.5, Saunderson 1942); k2 = 0.4-0.6 for paints (0.6 taken, Table III fits 0.59-0.63); ";
  const std::string t3 = "Abed, Berns & Masaoka 2013, Table III (coefficients optimised in Phase II; relative values, "
                         "not physical constants): ";
  std::vector<SaundersonPreset> presets = {
      {"d8-sci", "d:8, specular included (integrating sphere, SCI)", "measurement", {0.092, 0.6, 1.0},
       k_text + "k_ins = 1: the sphere returns the whole specular component to the detector"},
      {"d8-sce", "d:8, specular excluded (integrating sphere with light trap, SCE)", "measurement", {0.092, 0.6, 0.0},
       k_text + "k_ins = 0: the light trap removes the specular component"},
      {"45-0", "45°:0° (directional light at 45°, detector at the normal)", "both", {0.040, 0.6, 0.0},
       k_text + "k_ins = 0: the mirror direction misses the detector (the ISO 17321 capture geometry, one or two lamps)"},
      {"diffuse", "diffuse light (booth or sphere), camera at the normal", "capture", {0.092, 0.6, 0.0},
       k_text + "k_ins = 0 as a start: how much of the surface reflection of the booth's walls reaches the "
                "camera is what the fit finds (Table III: 0.24-1.0)"},
  };
  // Table III: per chart, the Eye-one (spectrophotometer) row, then the diffuse camera-taking row.
  struct TableIII {
    const char* id;
    const char* chart;
    const char* row;
    SaundersonGeometry eye_one, diffuse;
  };
  const TableIII table_iii[] = {
      {"classic", "ColorChecker Classic", "Classic", {0.04, 0.63, 0.30}, {0.07, 0.61, 0.24}},
      {"sg", "ColorChecker SG", "SG", {0.03, 0.60, 0.27}, {0.10, 0.59, 0.57}},
      {"matte", "custom matte patches", "Custom-Matte", {0.04, 0.61, 0.29}, {0.07, 0.59, 0.50}},
      {"glossy", "custom glossy patches", "Custom-Glossy", {0.07, 0.60, 0.00}, {0.05, 0.59, 1.00}},
  };
  for (const TableIII& t : table_iii) {
    const std::string id = std::string("t3-") + t.id, label = std::string("Table III, ") + t.chart;
    presets.push_back({id + "-eye-one", label + ", Eye-one 45°:0°", "measurement", t.eye_one,
                       t3 + t.row + " row, spectrophotometer geometry"});
    presets.push_back({id + "-diffuse", label + ", diffuse camera-taking", "capture", t.diffuse,
                       t3 + t.row + " row, camera-taking geometry"});
  }
  return presets;
}

}  // namespace

const std::vector<SaundersonPreset>& saunderson_presets() {
  return built_once<&build_presets>();
}

const SaundersonPreset& saunderson_preset(const std::string& id) {
  const auto id_of = [](const SaundersonPreset& p) { return p.id; };
  if (const SaundersonPreset* p = find_row(saunderson_presets(), id, id_of)) return *p;
  throw Error(ErrorCode::UnknownId,
              "unknown Saunderson preset '" + id + "' (presets: " + row_ids(saunderson_presets(), id_of) + ")");
}

}  // namespace tristim

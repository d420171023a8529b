// The colorimetry lab's exercises (rules in tristim/lab/exercises.hpp).
#include "tristim/lab/exercises.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/patch_files.hpp"
#include "tristim/lab/lab_options.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

PatchMatrix lab_patch_matrix(const std::vector<Vec3>& v) {
  PatchMatrix m(static_cast<Eigen::Index>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  return m;
}

SpectraToColour lab_spectra_to_colour(const std::string& chart, const std::string& patch,
                                      const std::vector<std::string>& illuminants_given,
                                      const std::vector<std::string>& observers_given) {
  // The exercise's lights (daylight, tungsten, a narrow-band fluorescent) and both CIE observers.
  const std::vector<std::string> illuminants =
      illuminants_given.empty() ? std::vector<std::string>{"D65", "A", "F11"} : illuminants_given;
  const std::vector<std::string> observers = observers_given.empty() ? std::vector<std::string>{"1931", "1964"} : observers_given;
  const SpectralData refl = chart_reflectances(chart);
  const std::string want = normalise_patch_id(patch);
  size_t k = refl.names.size();
  for (size_t i = 0; i < refl.names.size(); ++i)
    if (normalise_patch_id(refl.names[i]) == want) k = i;
  if (k == refl.names.size()) throw Error(ErrorCode::UnknownId, "chart " + chart + " has no patch '" + patch + "'");
  SpectraToColour out;
  out.chart = chart;
  out.patch = refl.names[k];
  out.wavelengths = refl.wavelengths;
  out.reflectance = refl.values[k];
  out.illuminants = illuminants;
  for (const auto& id : illuminants) {
    const SpectralData S = illuminant_spd(id);
    const auto s = interpolate_spectrum(S.wavelengths, S.values[0], refl.wavelengths, S.linear);
    const double s560 = interpolate_spectrum(S.wavelengths, S.values[0], {560.0}, S.linear)[0];
    std::vector<double> stim(s.size());
    for (size_t i = 0; i < s.size(); ++i) stim[i] = out.reflectance[i] * s[i] * 100 / s560;
    out.stimulus.push_back(stim);
    for (const auto& obs : observers) {
      const ReferenceChart ref = reference_chart(chart, id, parse_observer(obs));
      ColourRow r;
      r.illuminant = id;
      r.observer = observer_name(parse_observer(obs));
      r.XYZ = ref.XYZ[k];
      r.Lab = ref.Lab[k];
      const double sum = r.XYZ.sum();
      r.x = r.XYZ[0] / sum;
      r.y = r.XYZ[1] / sum;
      out.rows.push_back(r);
    }
  }
  return out;
}

namespace fields {
using R = OverfitRow;
TRISTIM_FIELDS_DEFINE(R, member<&R::model>("model"), member<&R::training>("training"), member<&R::terms>("terms"),
                      member<&R::patches>("patches"), member<&R::ok>("ok"), member<&R::error_code>("error_code"),
                      member<&R::message>("message"), member<&R::train_dE00>("train_dE00"),
                      member<&R::loo_dE00>("loo_dE00"), member<&R::test_dE00>("test_dE00"));
TRISTIM_FIELDS_DEFINE(LabTable, member<&LabTable::name>("name"), member<&LabTable::columns>("columns"),
                      member<&LabTable::rows>("rows"));
}  // namespace fields

json::Value overfit_row_json(const OverfitRow& row) {
  return fields::write_picked(row, {"model", "training", "terms", "patches", "ok", "error_code", "train_dE00",
                                    "loo_dE00", "test_dE00"});
}

SpectralData cmf_sensitivities() {
  SpectralData s = align_spectra(cmfs(Observer::CIE1931_2), wavelength_grid(380, 780, 5));
  s.names = {"R", "G", "B"};
  return s;
}

std::vector<OverfitRow> lab_overfit_exercise(const SpectralData& ssf, const SpectralData& illuminant,
                                             const OverfitOptions& o) {
  for (const auto& m : o.models) model_info(m);  // UnknownId before any work
  lab_option("overfit.noise", o.noise);
  Vec3 white;
  const SpectralData& munsell = munsell_reflectances();
  const PatchMatrix test_XYZ = lab_patch_matrix(reflectances_to_XYZ(munsell, illuminant, Observer::CIE1931_2, &white));
  const PatchMatrix test_RGB = lab_patch_matrix(simulate_camera_RGB(ssf, munsell, illuminant));
  std::vector<OverfitRow> out;
  for (const auto& chart : o.training) {
    const SpectralData refl = chart_reflectances(chart);
    SimulationOptions sim;
    sim.noise_sigma = o.noise;
    sim.seed = o.seed;
    const PatchMatrix rgb = lab_patch_matrix(simulate_camera_RGB(ssf, refl, illuminant, sim));
    const PatchMatrix xyz = lab_patch_matrix(reflectances_to_XYZ(refl, illuminant));
    FitOptions fo;
    fo.white = white;
    for (const auto& m : o.models) {
      OverfitRow r;
      r.model = m;
      r.training = chart;
      r.terms = model_info(m).n_terms;
      r.patches = static_cast<int>(rgb.rows());
      try {
        const ModelEvaluation e = evaluate_model(m, rgb, xyz, fo);
        r.ok = true;
        r.message = e.fit.message;
        r.train_dE00 = e.training.dE00.mean;
        r.loo_dE00 = e.has_loo ? e.loo.dE00.mean : std::numeric_limits<double>::quiet_NaN();
        r.test_dE00 = evaluate(predict(e.fit.model, test_RGB), test_XYZ, white).dE00.mean;
      } catch (const Error& err) {
        r.error_code = err.code_name();
        r.message = err.what();
      }
      out.push_back(r);
    }
  }
  return out;
}

std::string lab_number(double v) {
  if (!std::isfinite(v)) return {};
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string lab_table_csv(const LabTable& t) {
  auto cell = [](const std::string& v) {
    if (v.find_first_of(",\"\r\n") == std::string::npos) return v;
    std::string q = "\"";
    for (char c : v) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (size_t i = 0; i < cells.size(); ++i) s += (i ? "," : "") + cell(cells[i]);
    return s + "\n";
  };
  std::string out = line(t.columns);
  for (const auto& r : t.rows) out += line(r);
  return out;
}

}  // namespace tristim

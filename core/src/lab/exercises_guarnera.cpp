// The lab's exercise 5: Guarnera, Bianco & Schettini (2018) — exposure invariance of the colour
// transforms (eqs 13-15), HDR fusion (weighted, Algorithm 1) and Table 4, composed from the
// characterisation fit and the Absolute mode's virtual bracket and chain. Rules in
// tristim/lab/exercises.hpp.
#include <cmath>

#include "tristim/absolute/example.hpp"
#include "tristim/absolute/characterise.hpp"
#include "tristim/absolute/normalisation.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/absolute/report.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/linearisation/oecf_Shen2008.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

/// Table 4 of the paper (NRMSE X, Y, Z): single shot, multiple shot; D65, ILS (~A), CWF (~F2).
Vec3 paper_nrmse(const std::string& light, bool multiple) {
  if (light == "D65") return multiple ? Vec3(0.0128, 0.0119, 0.0175) : Vec3(0.0136, 0.0131, 0.0189);
  if (light == "A") return multiple ? Vec3(0.0070, 0.0064, 0.0091) : Vec3(0.0110, 0.0104, 0.0125);
  if (light == "F2") return multiple ? Vec3(0.0151, 0.0141, 0.0183) : Vec3(0.0177, 0.0164, 0.0209);
  return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
}

}  // namespace

std::vector<ExposureRow> lab_exposure_exercise(const SpectralData& ssf, const SpectralData& illuminant,
                                               const std::vector<std::string>& models_given,
                                               const std::vector<double>& ks_given) {
  // The paper's three transforms (eqs 11-15) and a polynomial with an offset; k from 1/8 to 8.
  const std::vector<std::string> models =
      models_given.empty()
          ? std::vector<std::string>{"Guarnera2018-T1", "Guarnera2018-To", "Guarnera2018-T2R", "Cheung2004-10"}
          : models_given;
  const std::vector<double> ks = ks_given.empty() ? std::vector<double>{0.125, 0.25, 0.5, 1, 2, 4, 8} : ks_given;
  for (const auto& m : models) model_info(m);  // UnknownId before any work
  for (double k : ks)
    if (!(k > 0 && k <= 1000)) throw Error(ErrorCode::InvalidArgument, "exposure factors k must be in (0, 1000]");
  const SpectralData refl = chart_reflectances("cc24");
  Vec3 white;
  const PatchMatrix train_RGB = lab_patch_matrix(simulate_camera_RGB(ssf, refl, illuminant));
  const PatchMatrix train_XYZ = lab_patch_matrix(reflectances_to_XYZ(refl, illuminant, Observer::CIE1931_2, &white));
  const SpectralData& munsell = munsell_reflectances();
  const PatchMatrix test_RGB = lab_patch_matrix(simulate_camera_RGB(ssf, munsell, illuminant));
  const PatchMatrix test_XYZ = lab_patch_matrix(reflectances_to_XYZ(munsell, illuminant));
  std::vector<ExposureRow> out;
  for (const auto& m : models) {
    const FitResult f = fit(m, train_RGB, train_XYZ);  // at k = 1
    for (double k : ks) {
      // Exposure × k: every camera value and every tristimulus value × k, the white too.
      const Metrics e = evaluate(predict(f.model, PatchMatrix(k * test_RGB)), PatchMatrix(k * test_XYZ), Vec3(k * white));
      out.push_back({m, k, e.dE00.mean, e.dE00.max});
    }
  }
  return out;
}

LabTable exposure_table(const std::vector<ExposureRow>& rows) {
  LabTable t{"lab-guarnera-exposure", {"model", "k (exposure factor)", "dE00 mean (CIEDE2000, 1269 Munsell chips)", "dE00 max"}, {}};
  for (const auto& r : rows)
    t.rows.push_back({r.model, lab_number(r.k), lab_number(r.dE00_mean), lab_number(r.dE00_max)});
  return t;
}

std::vector<GuarneraRow> lab_guarnera_table4(const std::string& camera, const std::vector<std::string>& lights,
                                             const std::vector<std::string>& trainings) {
  std::vector<GuarneraRow> out;
  for (const auto& light : lights)
    for (const auto& training : trainings) {
      AbsoluteExampleOptions o;
      o.camera = camera;
      o.illuminant = light;
      o.colour_training = training;
      o.cell = 16;  // 16-pixel cells (the example: 32): 4x fewer pixels to fuse, NRMSE within 0.0015 of 32
      const AbsoluteExample ex = make_absolute_example(o);  // the coded errors of a bad camera, light, training
      std::string transform = "T1";
      for (const auto& c : example_training_table())
        if (c.id == training && !c.transform.empty()) transform = c.transform;
      // Fitted as a user would: n from the lens cap, S measured on the bracket, f(r) from the flat.
      std::vector<const RawImage*> caps, series;
      for (const auto& c : ex.lens_cap) caps.push_back(&c);
      for (const auto& f : ex.frames) series.push_back(&f);
      const DarkFrame cap = average_dark_frames(caps);
      const Normalisation n = make_normalisation(&cap, measure_saturation(series), &ex.sensor.ssf,
                                                 fit_falloff_Guarnera2018(ex.flat, &cap), 10);
      std::vector<TrainingStimulus> stimuli = ex.stimuli;
      for (auto& s : stimuli)
        for (int c = 0; c < 3; ++c) s.saturated[c] = n.zone(c, s.raw_RGB[c]) == Zone::Saturated;
      AbsoluteFitOptions fo;
      fo.transform = transform;
      AbsoluteProfile p = fit_absolute_Guarnera2018(stimuli, n, fo);
      const std::vector<AbsoluteStimulus> test = read_absolute_stimuli(ex.test_csv, "the example's test scene");
      for (const char* shots : {"single", "weighted", "recursive"}) {
        const bool single = std::string(shots) == "single";
        p.fusion = std::string(shots) == "recursive" ? FusionMode::Recursive : FusionMode::Weighted;
        // The Absolute mode's evaluation of the example's test scene (its cells as region rows of
        // the middle frame, measured on the maps over their central half; white per eq 16): the
        // chromatic rows' figures are the 24 ColorChecker cells'.
        AbsoluteApplyOptions ao;
        ao.names = ex.frame_names;
        std::vector<const RawImage*> frames = series;
        if (single) {
          frames = {series[series.size() / 2]};
          ao.names = {ex.frame_names[series.size() / 2]};
        }
        const AbsoluteMaps maps = apply_absolute_series(p, frames, ao);
        const AbsoluteTestReport rep = evaluate_absolute_test(p, &maps, test);
        AbsoluteMetrics m;
        for (const auto& f : rep.figures)
          if (f.group == "colour") m = f.metrics;
        GuarneraRow r;
        r.light = light;
        r.training = training;
        r.transform = transform;
        r.shots = shots;
        r.NRMSE = m.metrics.NRMSE;
        r.dE00_mean = m.metrics.dE00.mean;
        r.relative_Y_error = m.relative_Y_error;
        r.paper_NRMSE = paper_nrmse(light, !single);
        out.push_back(r);
      }
    }
  return out;
}

LabTable guarnera_table(const std::vector<GuarneraRow>& rows) {
  LabTable t{"lab-guarnera-table4",
             {"light", "colour training", "transform", "shots", "NRMSE X (fraction of the range)", "NRMSE Y", "NRMSE Z",
              "dE00 mean (CIEDE2000, white eq 16)", "relative Y error (mean, fraction)", "paper NRMSE X", "paper NRMSE Y",
              "paper NRMSE Z"},
             {}};
  for (const auto& r : rows)
    t.rows.push_back({r.light, r.training, r.transform, r.shots, lab_number(r.NRMSE[0]), lab_number(r.NRMSE[1]), lab_number(r.NRMSE[2]), lab_number(r.dE00_mean),
                      lab_number(r.relative_Y_error), lab_number(r.paper_NRMSE[0]), lab_number(r.paper_NRMSE[1]), lab_number(r.paper_NRMSE[2])});
  return t;
}

}  // namespace tristim

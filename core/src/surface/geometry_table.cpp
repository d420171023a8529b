// Abed, Berns & Masaoka 2013 Table IV: five methods, train on one chart, test on another; and the
// simulated experiment (virtual camera + Saunderson forward model).
#include "tristim/surface/geometry_table.hpp"

#include <algorithm>

#include "tristim/characterisation/fit.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/surface/joint.hpp"
#include "tristim/surface/options_table.hpp"
#include "tristim/surface/surface.hpp"

namespace tristim {

namespace {

PatchMatrix to_matrix(const std::vector<Vec3>& rows) {
  PatchMatrix m(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  return m;
}

SpectralData illuminant_or_D50(const SpectralData& s) { return s.size() ? s : illuminant_spd("D50"); }

}  // namespace

GeometryChart simulate_geometry_chart(const std::string& name, const SpectralData& spectra,
                                      const SaundersonGeometry& measurement, const SaundersonGeometry& capture,
                                      const GeometryScene& scene) {
  check_reflectances(spectra, name);
  GeometryChart c;
  c.name = name;
  c.ids = spectra.names;
  c.measured = spectra;
  c.seen = spectra;
  for (size_t k = 0; k < spectra.size(); ++k)
    for (size_t w = 0; w < spectra.wavelengths.size(); ++w) {
      const double internal = std::max(0.0, saunderson_internal_Abed2013(spectra.values[k][w], measurement));  // eq (2)
      c.measured.values[k][w] = saunderson_measured_Abed2013(internal, measurement);                          // eq (1)
      c.seen.values[k][w] = saunderson_measured_Abed2013(internal, capture);                                  // eq (1)
    }
  const SpectralData illuminant = illuminant_or_D50(scene.illuminant);
  c.camera_RGB = to_matrix(simulate_camera_RGB(scene.ssf, c.seen, illuminant, scene.camera));
  c.seen_XYZ = to_matrix(reflectances_to_XYZ(c.seen, illuminant, scene.observer));
  return c;
}

Vec3 simulate_white_RGB(const GeometryScene& scene) {
  SpectralData white;
  white.wavelengths = {300, 830};
  white.names = {"white"};
  white.values = {{scene.white_reflectance, scene.white_reflectance}};
  SimulationOptions o = scene.camera;
  o.noise_sigma = 0;  // a white reference is averaged over many pixels
  return simulate_camera_RGB(scene.ssf, white, illuminant_or_D50(scene.illuminant), o)[0];
}

GeometryChart combine_charts(const std::string& name, const GeometryChart& a, const GeometryChart& b) {
  // One grid: the one with fewer wavelengths; the other set is interpolated onto it (spectra.hpp rule).
  const std::vector<double>& grid =
      a.measured.wavelengths.size() <= b.measured.wavelengths.size() ? a.measured.wavelengths : b.measured.wavelengths;
  GeometryChart c;
  c.name = name;
  c.measured.wavelengths = c.seen.wavelengths = grid;
  for (const GeometryChart* x : {&a, &b}) {
    const SpectralData measured = align_spectra(x->measured, grid), seen = align_spectra(x->seen, grid);
    for (size_t i = 0; i < x->ids.size(); ++i) {
      c.ids.push_back(x->name + ":" + x->ids[i]);
      c.measured.names.push_back(c.ids.back());
      c.seen.names.push_back(c.ids.back());
      c.measured.values.push_back(measured.values[i]);
      c.seen.values.push_back(seen.values[i]);
    }
  }
  c.camera_RGB.resize(a.camera_RGB.rows() + b.camera_RGB.rows(), 3);
  c.camera_RGB << a.camera_RGB, b.camera_RGB;
  c.seen_XYZ.resize(a.seen_XYZ.rows() + b.seen_XYZ.rows(), 3);
  c.seen_XYZ << a.seen_XYZ, b.seen_XYZ;
  return c;
}

std::vector<std::string> geometry_table_methods() {
  return {"scaler-offset", "saunderson", "matrix-3x3", "matrix-3x4", "corrected-3x3"};
}

std::vector<GeometryTableCell> geometry_table_Abed2013(const std::vector<GeometryChart>& training,
                                                       const GeometryChart& test, const GeometryTableOptions& options) {
  const SpectralData illuminant = illuminant_or_D50(options.illuminant);
  const Vec3 white = illuminant_white_XYZ(illuminant, options.observer);
  if (test.seen_XYZ.rows() != test.camera_RGB.rows() || test.camera_RGB.rows() == 0)
    throw Error(ErrorCode::PatchMismatch, "test chart '" + test.name + "': camera RGB and XYZ do not pair up");
  JointFitOptions joint;
  joint.illuminant = illuminant;
  joint.observer = options.observer;
  joint.white_RGB = options.white_RGB;
  joint.white_reflectance = options.white_reflectance;
  std::vector<GeometryTableCell> cells;
  for (const GeometryChart& chart : training) {
    const PatchMatrix instrument_XYZ = to_matrix(reflectances_to_XYZ(chart.measured, illuminant, options.observer));
    for (const std::string& method : geometry_table_methods()) {
      GeometryTableCell cell;
      cell.training = chart.name;
      cell.method = method;
      try {
        if (method == "scaler-offset" || method == "saunderson") {
          const MethodChoice start = method == "saunderson" ? options.saunderson : MethodChoice{method, {}, {}};
          const JointFitResult r = fit_surface_joint_Abed2013(start, chart.camera_RGB, chart.measured, joint);
          cell.matrix = r.matrix;
          cell.correction = r.choice;
          cell.status = r.status;
          cell.message = r.message;
        } else if (method == "corrected-3x3") {
          const CorrectedMatrix m = fit_corrected_3x3_Abed2013(chart.camera_RGB, instrument_XYZ, options.white_RGB,
                                                               options.white_reflectance * white);
          cell.matrix = m.matrix;
          cell.mu = m.mu;
        } else {
          const FitResult f = fit(method, chart.camera_RGB, instrument_XYZ);
          cell.matrix = f.model.coefficients.leftCols<3>();
          cell.status = fit_status_name(f.status);
          cell.message = f.message;
          if (method == "matrix-3x4") {  // the offset column is applied below
            const PatchMatrix predicted = predict(f.model, test.camera_RGB);
            const Metrics m = evaluate(predicted / 100.0, test.seen_XYZ / 100.0, white / 100.0);
            cell.dE_xyz = m.dE_xyz;
            cell.dE00 = m.dE00;
            cell.ok = true;
            cells.push_back(cell);
            continue;
          }
        }
        const PatchMatrix predicted = test.camera_RGB * cell.matrix.transpose();
        const Metrics m = evaluate(predicted / 100.0, test.seen_XYZ / 100.0, white / 100.0);
        cell.dE_xyz = m.dE_xyz;
        cell.dE00 = m.dE00;
        cell.ok = true;
      } catch (const Error& e) {
        cell.ok = false;
        cell.error_code = e.code_name();
        cell.message = e.what();
      }
      cells.push_back(cell);
    }
  }
  return cells;
}

GeometryExperiment geometry_experiment_Abed2013(const std::string& camera, const std::string& illuminant_id,
                                                double noise_sigma, uint64_t seed) {
  check_surface_option("noise", noise_sigma);
  GeometryExperiment x;
  x.scene.ssf = camera_ssf(camera);
  x.scene.illuminant = illuminant_spd(illuminant_id);
  x.scene.camera.noise_sigma = noise_sigma;
  x.scene.camera.seed = seed;
  auto pair = [](const char* a) { return saunderson_preset(a).geometry; };
  const GeometryChart classic = simulate_geometry_chart("Classic", chart_reflectances("cc24-2005"),
                                                        pair("t3-classic-eye-one"), pair("t3-classic-diffuse"), x.scene);
  x.scene.camera.seed = seed + 1;
  const GeometryChart sg = simulate_geometry_chart("SG", chart_reflectances("sg140-2005"), pair("t3-sg-eye-one"),
                                                   pair("t3-sg-diffuse"), x.scene);
  x.scene.camera.seed = seed + 2;
  const GeometryChart glossy = simulate_geometry_chart("Glossy", chart_reflectances("sg140"), pair("t3-glossy-eye-one"),
                                                       pair("t3-glossy-diffuse"), x.scene);
  x.scene.camera.seed = seed + 3;
  x.test = simulate_geometry_chart("Matte test", chart_reflectances("cc24"), pair("t3-matte-eye-one"),
                                   pair("t3-matte-diffuse"), x.scene);
  x.scene.camera.seed = seed;
  x.training = {classic, sg, glossy, combine_charts("Total", classic, sg)};
  x.options.illuminant = x.scene.illuminant;
  x.options.observer = x.scene.observer;
  x.options.white_reflectance = x.scene.white_reflectance;
  x.options.white_RGB = simulate_white_RGB(x.scene);
  const SaundersonGeometry instrument = saunderson_preset("45-0").geometry;
  x.options.saunderson = surface_choice("saunderson", {instrument.k1, instrument.k2, instrument.k_ins, instrument.k1,
                                                       instrument.k2, instrument.k_ins});
  return x;
}

}  // namespace tristim

// The simulation of Shen, Xin, Yang & Lou (2008) eq (29), shared by the Catch2 suite and
// examples/linearisation/shen2008_simulation.cpp (no test framework, no files).
#pragma once
#include <cstdint>
#include <string>

#include "tristim/chart/reference.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::test {

/// One noise realisation of eq (29): ρ = l·u^(1/γ) + n, γ = 1.8, l = 22, n ~ N(0, sigma²) drawn
/// from `seed`, ρ clipped to [0, 255] (and rounded when `quantise`), `camera`'s measured
/// sensitivities under D65; the perfect diffuser's linear G response u = 80 puts white near
/// ρ = 251. Reference XYZ: the chart's reflectances under D65, CIE 1931 2°.
inline LinearisationData shen2008_simulation(const std::string& chart, double sigma, std::uint64_t seed,
                                             const std::string& camera, bool quantise) {
  const SpectralData refl = chart_reflectances(chart);
  const SpectralData d65 = illuminant_spd("D65");
  const ReferenceChart ref = reference_from_spectra(refl, d65, Observer::CIE1931_2);
  SimulationOptions o;
  o.white_level = 80;
  o.oecf = true;  // defaults γ = 1.8, l = 22
  o.noise_sigma = sigma;
  o.seed = seed;
  o.clip_max = 255;
  o.quantise = quantise;
  const auto rgb = simulate_camera_RGB(camera_ssf(camera), refl, d65, o);
  LinearisationData d;
  d.ids = refl.names;
  d.reflectances = refl;
  d.full_scale = 255;
  d.white = ref.white;
  d.camera_RGB.resize(static_cast<Eigen::Index>(rgb.size()), 3);
  d.reference_XYZ.resize(static_cast<Eigen::Index>(rgb.size()), 3);
  for (size_t i = 0; i < rgb.size(); ++i) {
    d.camera_RGB.row(static_cast<Eigen::Index>(i)) = rgb[i].transpose();
    d.reference_XYZ.row(static_cast<Eigen::Index>(i)) = ref.XYZ[i].transpose();
  }
  return d;
}

/// The grey patches as the paper divides the charts: the ColorChecker's six (D1-D6); for other
/// charts "" (the automatic rule).
inline std::string shen2008_greys(const std::string& chart) {
  return chart.rfind("cc24", 0) == 0 ? "D1;D2;D3;D4;D5;D6" : "";
}

}  // namespace tristim::test

// The virtual bracket camera (rules in tristim/absolute/virtual_bracket.hpp).
#include "tristim/absolute/virtual_bracket.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "../detmath.hpp"
#include "tristim/error.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

struct StimulusResponse {
  std::array<double, 3> q;  // per cd/m²
  Vec3 xyz_per_Y;           // X/Y, 1, Z/Y
};

std::vector<double> cmf_on(const std::vector<double>& grid, int k) {
  const SpectralData& c = cmfs(Observer::CIE1931_2);
  return interpolate_spectrum(c.wavelengths, c.values[k], grid);
}

std::vector<StimulusResponse> responses(const VirtualSensor& s, const VirtualScene& scene) {
  if (s.ssf.size() != 3) throw Error(ErrorCode::InvalidArgument, "virtual camera: sensitivities need R, G, B");
  const auto& grid = s.ssf.wavelengths;
  const auto xbar = cmf_on(grid, 0), ybar = cmf_on(grid, 1), zbar = cmf_on(grid, 2);
  double sum_y = 0, sum_G = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    sum_y += ybar[i];
    sum_G += s.ssf.values[1][i];
  }
  std::vector<StimulusResponse> out;
  for (const auto& col : scene.stimuli.values) {
    const auto phi = interpolate_spectrum(scene.stimuli.wavelengths, col, grid, scene.stimuli.linear);
    double X = 0, Y = 0, Z = 0, C[3] = {0, 0, 0};
    for (size_t i = 0; i < grid.size(); ++i) {
      X += xbar[i] * phi[i];
      Y += ybar[i] * phi[i];
      Z += zbar[i] * phi[i];
      for (int c = 0; c < 3; ++c) C[c] += s.ssf.values[c][i] * phi[i];
    }
    if (!(Y > 0)) throw Error(ErrorCode::InvalidArgument, "virtual camera: a stimulus has no luminance");
    StimulusResponse r;
    for (int c = 0; c < 3; ++c) r.q[c] = C[c] / Y * sum_y / sum_G;
    r.xyz_per_Y = Vec3(X / Y, 1.0, Z / Y);
    out.push_back(r);
  }
  return out;
}

void check_scene(const VirtualScene& scene) {
  const size_t n = static_cast<size_t>(scene.width) * scene.height;
  if (scene.width <= 0 || scene.height <= 0 || scene.label.size() != n)
    throw Error(ErrorCode::InvalidArgument, "virtual scene: label map does not match its size");
  if (!scene.gain.empty() && scene.gain.size() != n)
    throw Error(ErrorCode::InvalidArgument, "virtual scene: gain map does not match its size");
  if (scene.luminance.size() != scene.stimuli.size())
    throw Error(ErrorCode::InvalidArgument, "virtual scene: one luminance per stimulus is needed");
  for (auto l : scene.label)
    if (l >= scene.stimuli.size()) throw Error(ErrorCode::InvalidArgument, "virtual scene: label outside the stimuli");
}

}  // namespace

SpectralData reflected_spectra(const SpectralData& reflectances, const SpectralData& illuminant) {
  SpectralData out = reflectances;
  out.linear = false;
  const auto S = interpolate_spectrum(illuminant.wavelengths, illuminant.values[0], reflectances.wavelengths,
                                      illuminant.linear);
  for (auto& col : out.values)
    for (size_t i = 0; i < col.size(); ++i) col[i] *= S[i];
  return out;
}

SpectralData equal_energy_spectrum(const std::string& name) {
  SpectralData d;
  d.wavelengths = wavelength_grid(380, 780, 5);
  d.names = {name};
  d.values = {std::vector<double>(d.wavelengths.size(), 1.0)};
  return d;
}

SpectralData projector_primaries() {
  SpectralData d;
  d.wavelengths = wavelength_grid(380, 780, 5);
  const auto& g = d.wavelengths;
  auto band = [&](double lo, double hi) {
    std::vector<double> v(g.size());
    for (size_t i = 0; i < g.size(); ++i)
      v[i] = 1.0 / (1.0 + detmath::exp(-(g[i] - lo) / 8.0)) / (1.0 + detmath::exp((g[i] - hi) / 8.0));
    return v;
  };
  d.names = {"R", "G", "B"};
  d.values = {band(580, 700), band(490, 580), band(400, 500)};
  return d;
}

SpectralData projector_spectra(const std::vector<Vec3>& targets, const std::vector<std::string>& names) {
  const SpectralData prim = projector_primaries();
  SpectralData d;
  d.wavelengths = prim.wavelengths;
  const auto& g = d.wavelengths;
  const std::vector<double>* P = prim.values.data();
  const auto xbar = cmf_on(g, 0), ybar = cmf_on(g, 1), zbar = cmf_on(g, 2);
  Mat3 M;  // column k: XYZ of primary k
  for (int k = 0; k < 3; ++k) {
    Vec3 xyz = Vec3::Zero();
    for (size_t i = 0; i < g.size(); ++i) xyz += Vec3(xbar[i], ybar[i], zbar[i]) * P[k][i];
    M.col(k) = xyz;
  }
  const Mat3 Minv = M.inverse();
  for (size_t t = 0; t < targets.size(); ++t) {
    Vec3 w = Minv * targets[t];
    if (w.minCoeff() < 0) {  // outside the gamut: least squares with the negative weights removed
      std::vector<int> keep;
      for (int k = 0; k < 3; ++k)
        if (w[k] > 0) keep.push_back(k);
      Eigen::MatrixXd A(3, keep.size());
      for (size_t j = 0; j < keep.size(); ++j) A.col(j) = M.col(keep[j]);
      const Eigen::VectorXd x = A.colPivHouseholderQr().solve(targets[t]);
      w.setZero();
      for (size_t j = 0; j < keep.size(); ++j) w[keep[j]] = std::max(0.0, x[j]);
    }
    std::vector<double> phi(g.size(), 0.0);
    for (int k = 0; k < 3; ++k)
      for (size_t i = 0; i < g.size(); ++i) phi[i] += w[k] * P[k][i];
    d.values.push_back(phi);
    d.names.push_back(t < names.size() ? names[t] : std::to_string(t + 1));
  }
  return d;
}

VirtualScene uniform_scene(int width, int height, const SpectralData& spectrum, double luminance) {
  VirtualScene s;
  s.width = width;
  s.height = height;
  s.stimuli = spectrum;
  s.stimuli.names.resize(1);
  s.stimuli.values.resize(1);
  s.luminance = {luminance};
  s.label.assign(static_cast<size_t>(width) * height, 0);
  return s;
}

Vec3 virtual_XYZ(const VirtualSensor& sensor, const VirtualScene& scene, int k, double gain) {
  const auto r = responses(sensor, scene);
  if (k < 0 || k >= static_cast<int>(r.size())) throw Error(ErrorCode::InvalidArgument, "virtual scene: no such stimulus");
  return r[k].xyz_per_Y * scene.luminance[k] * gain;
}

namespace {

// Calls block(x, y, v) for every measurement pixel with its sensor values v = {R, G1, G2, B}
// (the noise drawn in that order, pixel after pixel).
template <class Block>
void simulate_blocks(const VirtualSensor& s, const VirtualScene& scene, const ExposureSettings& e, std::uint64_t seed,
                     Block block) {
  check_scene(scene);
  if (!(e.exposure_s > 0 && e.f_number > 0))
    throw Error(ErrorCode::InvalidArgument, "virtual camera: exposure time and f-number must be > 0");
  if (!(s.saturation > s.noise_floor) || !(s.saturation_exposure > 0))
    throw Error(ErrorCode::InvalidArgument, "virtual camera: saturation must exceed the noise floor");
  const auto resp = responses(s, scene);
  constexpr double t_ref = 1.0 / 60;
  const double eps = t_ref * detmath::pow(e.exposure_s / t_ref, s.reciprocity_exponent) / (e.f_number * e.f_number) *
                     (e.iso > 0 ? e.iso / 100.0 : 1.0);
  const double range = s.saturation - s.noise_floor;
  const double electrons = s.electrons_per_dn * range;  // at u = 1
  GaussianNoise noise(seed);
  const double cx = scene.width / 2.0, cy = scene.height / 2.0, r_scale = std::sqrt(cx * cx + cy * cy);
  auto sensor_value = [&](int c, double u) {
    if (electrons > 0) {
      const double el = u * electrons;
      u = (el + std::sqrt(std::max(el, 0.0)) * noise.next()) / electrons;  // shot noise
    }
    const double v = u < 0 ? -detmath::pow(-u, s.oecf_exponent[c]) : detmath::pow(u, s.oecf_exponent[c]);  // OECF
    double dn = s.noise_floor + range * v + s.read_noise * noise.next();
    dn = std::min(dn, s.saturation);
    return s.quantise ? std::round(dn) : dn;
  };
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const size_t p = static_cast<size_t>(y) * scene.width + x;
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy, r = std::sqrt(dx * dx + dy * dy) / r_scale;
      const double f = s.falloff_p1 * r * r + s.falloff_p2 * r + 1.0;
      const int k = scene.label[p];
      const double Y = scene.luminance[k] * (scene.gain.empty() ? 1.0 : scene.gain[p]);
      const double base = Y * eps / s.saturation_exposure / f;
      double v[4];
      v[0] = sensor_value(0, base * resp[k].q[0]);
      v[1] = sensor_value(1, base * resp[k].q[1]);
      v[2] = sensor_value(1, base * resp[k].q[1]);
      v[3] = sensor_value(2, base * resp[k].q[2]);
      block(x, y, v);
    }
}

}  // namespace

TrainingStimulus shoot_colour_stimulus(const VirtualSensor& sensor, const SpectralData& spectra, size_t k,
                                       double luminance, int width, int height, const ExposureSettings& exposure,
                                       std::uint64_t seed, const Normalisation& n, const std::string& id) {
  VirtualScene scene = uniform_scene(width, height, spectra, luminance);
  scene.stimuli.values = {spectra.values[k]};
  scene.stimuli.names = {spectra.names[k]};
  const RawImage frame = capture_virtual(sensor, scene, exposure, seed);
  return sample_stimulus(frame, width / 2 - 4, height / 2 - 4, 8, 8, n, exposure, virtual_XYZ(sensor, scene, 0), id,
                         false);
}

RawImage capture_virtual(const VirtualSensor& s, const VirtualScene& scene, const ExposureSettings& e,
                         std::uint64_t seed) {
  RawImage img;
  img.width = scene.width;
  img.height = scene.height;
  RawMetadata& m = img.meta;
  m.make = s.make;
  m.model = s.model;
  m.iso = e.iso;
  m.shutter_s = e.exposure_s;
  m.f_number = e.f_number;
  m.layout = "bayer";
  m.cfa_pattern = "RGGB";
  m.cfa_width = m.cfa_height = 2;
  m.block = 2;
  m.width = scene.width;
  m.height = scene.height;
  m.sensor_width = m.raw_width = 2 * scene.width;
  m.sensor_height = m.raw_height = 2 * scene.height;
  m.bits = 14;
  m.white_level = s.reported_saturation;
  m.saturation = {s.reported_saturation, s.reported_saturation, s.reported_saturation};
  m.decoder = "virtual_bracket";
  const size_t npix = static_cast<size_t>(scene.width) * scene.height;
  img.rgb.resize(npix * 3);
  img.saturated.assign(npix, 0);
  const double flag_level = 0.98 * s.reported_saturation;  // decode_raw's rule
  simulate_blocks(s, scene, e, seed, [&](int x, int y, const double* v) {
    const size_t p = static_cast<size_t>(y) * scene.width + x;
    img.rgb[p * 3] = static_cast<float>(v[0]);
    img.rgb[p * 3 + 1] = static_cast<float>(0.5 * (v[1] + v[2]));
    img.rgb[p * 3 + 2] = static_cast<float>(v[3]);
    std::uint8_t flags = 0;
    if (v[0] >= flag_level) flags |= 1;
    if (v[1] >= flag_level || v[2] >= flag_level) flags |= 2;
    if (v[3] >= flag_level) flags |= 4;
    img.saturated[p] = flags;
  });
  return img;
}

std::vector<std::uint16_t> capture_virtual_mosaic(const VirtualSensor& s, const VirtualScene& scene,
                                                  const ExposureSettings& e, std::uint64_t seed, int black) {
  const size_t W = 2 * static_cast<size_t>(scene.width);
  std::vector<std::uint16_t> out(W * 2 * scene.height);
  auto dn = [black](double v) { return static_cast<std::uint16_t>(std::clamp(std::round(v) + black, 0.0, 65535.0)); };
  simulate_blocks(s, scene, e, seed, [&](int x, int y, const double* v) {
    const size_t r0 = 2 * static_cast<size_t>(y) * W + 2 * x;  // RGGB
    out[r0] = dn(v[0]);
    out[r0 + 1] = dn(v[1]);
    out[r0 + W] = dn(v[2]);
    out[r0 + W + 1] = dn(v[3]);
  });
  return out;
}

}  // namespace tristim

// Test bench of the absolute chain (Guarnera 2018 section 4, run on the virtual bracket camera):
// lens-cap frames, a flat field for the fall-off, the luminance training set (equal-tristimulus
// projector light, 0-890 cd/m² in 30 cd/m² steps, photographed at every exposure of the bracket),
// the 24 projected ColorChecker colours for the matrix, and test scenes (a ColorChecker under
// D65, A and F2 filling the frame). Everything is generated at test time.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "absolute_training_chart.hpp"
#include "synthetic.hpp"
#include "tristim/absolute/profile.hpp"
#include "tristim/absolute/virtual_bracket.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim::test {

/// The bracket: 1/250 … 1/15 s at f/8, ISO 100 (one-stop steps; the paper doubles t).
inline std::vector<ExposureSettings> default_bracket() {
  return {{1.0 / 250, 8, 100}, {1.0 / 125, 8, 100}, {1.0 / 60, 8, 100}, {1.0 / 30, 8, 100}, {1.0 / 15, 8, 100}};
}

struct BenchConfig {
  std::string camera = "Canon_EOS_5D_Mark_II";
  double reciprocity_exponent = 1;
  std::string transform = "T1";
  std::array<double, 3> oecf_exponent{{1.03, 1.0, 0.97}};
};

struct AbsoluteBench {
  VirtualSensor sensor;
  std::vector<ExposureSettings> bracket;
  DarkFrame cap;
  FalloffFit falloff;
  SaturationEstimate saturation;
  Normalisation normalisation;
  std::vector<TrainingStimulus> stimuli;
  AbsoluteProfile profile;
};

inline VirtualSensor bench_sensor(const BenchConfig& c) {
  VirtualSensor s;
  s.ssf = camera_ssf(c.camera);
  s.model = "Virtual " + c.camera;
  s.reciprocity_exponent = c.reciprocity_exponent;
  s.oecf_exponent = c.oecf_exponent;
  return s;
}

inline AbsoluteBench build_bench(const BenchConfig& config) {
  AbsoluteBench b;
  b.sensor = bench_sensor(config);
  b.bracket = default_bracket();
  const int W = 60, H = 40;
  const ExposureSettings mid = b.bracket[2];
  std::uint64_t seed = 1000;
  // Lens-cap frames (Y = 0) and a flat field (equal-tristimulus light, about half scale).
  const SpectralData E = projector_spectra({Vec3(1, 1, 1)}, {"E"});
  std::vector<RawImage> caps;
  for (int i = 0; i < 4; ++i) caps.push_back(capture_virtual(b.sensor, uniform_scene(W, H, E, 0.0), mid, seed++));
  std::vector<const RawImage*> cap_ptrs;
  for (const auto& c : caps) cap_ptrs.push_back(&c);
  b.cap = average_dark_frames(cap_ptrs);
  const RawImage flat = capture_virtual(b.sensor, uniform_scene(4 * W, 4 * H, E, 450.0), mid, seed++);
  b.falloff = fit_falloff_Guarnera2018(flat, nullptr);
  // Luminance training: every stimulus at every exposure (the frames are kept to measure S).
  std::vector<RawImage> frames;
  std::vector<std::pair<double, int>> meta;  // Y, exposure index
  for (double Y : training_luminances())
    for (size_t e = 0; e < b.bracket.size(); ++e) {
      frames.push_back(capture_virtual(b.sensor, uniform_scene(W, H, E, Y), b.bracket[e], seed++));
      meta.push_back({Y, static_cast<int>(e)});
    }
  std::vector<const RawImage*> ptrs;
  for (const auto& f : frames) ptrs.push_back(&f);
  b.saturation = measure_saturation(ptrs);
  b.normalisation = make_normalisation(&b.cap, b.saturation, &b.sensor.ssf, std::nullopt, 10);
  // The flat was 4x the size: rescale its centre and r_scale to the training frames.
  b.normalisation.falloff = centred_falloff(b.falloff, W, H);
  for (size_t i = 0; i < frames.size(); ++i) {
    const double Y = meta[i].first;
    b.stimuli.push_back(sample_stimulus(frames[i], W / 2 - 4, H / 2 - 4, 8, 8, b.normalisation,
                                        b.bracket[meta[i].second], Vec3(Y, Y, Y),
                                        "Y" + std::to_string(static_cast<int>(Y)) + "@" + std::to_string(meta[i].second)));
  }
  // Colour training: the 24 ColorChecker colours (D65, white 700 cd/m²) projected on the target,
  // one shot each at the middle exposure.
  const ReferenceChart cc = reference_chart("cc24", "D65");
  std::vector<Vec3> targets;
  for (const auto& x : cc.XYZ) targets.push_back(x * 7.0);
  const SpectralData proj = projector_spectra(targets, cc.ids);
  for (size_t k = 0; k < targets.size(); ++k) {
    b.stimuli.push_back(shoot_colour_stimulus(b.sensor, proj, k, targets[k][1], W, H, mid, seed++, b.normalisation, cc.ids[k]));
  }
  AbsoluteFitOptions o;
  o.transform = config.transform;
  b.profile = fit_absolute_Guarnera2018(b.stimuli, b.normalisation, o);
  b.profile.make = b.sensor.make;
  b.profile.model = b.sensor.model;
  b.profile.saturation = b.saturation;
  b.profile.areas_source = "camera:" + config.camera;
  return b;
}

/// The bench for a configuration, built once per test run.
inline const AbsoluteBench& bench(const BenchConfig& config = {}) {
  static std::map<std::string, std::unique_ptr<AbsoluteBench>> cache;
  const std::string key = config.camera + "|" + std::to_string(config.reciprocity_exponent) + "|" + config.transform;
  auto& slot = cache[key];
  if (!slot) slot = std::make_unique<AbsoluteBench>(build_bench(config));
  return *slot;
}

/// The profile with the fall-off adapted to a frame size (the bench fits it on 60×40 frames;
/// f(r) is in relative radius, so only the centre and scale change).
inline AbsoluteProfile profile_for(const AbsoluteBench& b, int width, int height) {
  AbsoluteProfile p = b.profile;
  p.normalisation.falloff = centred_falloff(*p.normalisation.falloff, width, height);
  p.width = width;
  p.height = height;
  return p;
}

/// Stimuli laid out in a grid of `cell`-pixel cells, `columns` per row (row-major); the truth
/// per stimulus from the virtual camera.
struct GridScene {
  VirtualScene scene;
  std::vector<std::string> ids;
  std::vector<Vec3> XYZ;  ///< truth per stimulus, cd/m²
  int cell = 24, columns = 6;
};

inline GridScene grid_scene(const VirtualSensor& sensor, const SpectralData& spectra,
                            const std::vector<double>& luminance, int columns, int cell) {
  GridScene g;
  g.cell = cell;
  g.columns = columns;
  const int n = static_cast<int>(spectra.size()), rows = (n + columns - 1) / columns;
  g.scene.width = columns * cell;
  g.scene.height = rows * cell;
  g.scene.stimuli = spectra;
  g.scene.luminance = luminance;
  g.ids = spectra.names;
  g.scene.label.resize(static_cast<size_t>(g.scene.width) * g.scene.height);
  for (int y = 0; y < g.scene.height; ++y)
    for (int x = 0; x < g.scene.width; ++x)
      g.scene.label[static_cast<size_t>(y) * g.scene.width + x] =
          static_cast<std::uint16_t>(std::min(n - 1, (y / cell) * columns + x / cell));
  for (int k = 0; k < n; ++k) g.XYZ.push_back(virtual_XYZ(sensor, g.scene, k));
  return g;
}

/// Y of a spectrum up to one constant (Σ ȳ·φ on its own grid).
inline double luminance_sum(const SpectralData& spectra, int k) {
  const SpectralData& cm = cmfs(Observer::CIE1931_2);
  const auto ybar = interpolate_spectrum(cm.wavelengths, cm.values[1], spectra.wavelengths);
  double s = 0;
  for (size_t i = 0; i < ybar.size(); ++i) s += ybar[i] * spectra.values[k][i];
  return s;
}

/// A ColorChecker under an illuminant filling a 6 × 4 grid, the white patch (D1) at `white_Y`.
inline GridScene chart_scene(const VirtualSensor& sensor, const std::string& illuminant, double white_Y = 600,
                             int cell = 24) {
  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData spectra = reflected_spectra(refl, illuminant_spd(illuminant));
  int white = 0;
  for (size_t k = 0; k < refl.names.size(); ++k)
    if (refl.names[k] == "D1") white = static_cast<int>(k);
  const double yw = luminance_sum(spectra, white);
  std::vector<double> Y;
  for (size_t k = 0; k < spectra.size(); ++k) Y.push_back(white_Y * luminance_sum(spectra, static_cast<int>(k)) / yw);
  return grid_scene(sensor, spectra, Y, 6, cell);
}
using ChartScene = GridScene;

/// Mean X, Y, Z over the central half of each cell (NaN pixels skipped).
inline PatchMatrix patch_means(const std::vector<float>& XYZ, const GridScene& c) {
  PatchMatrix out(c.ids.size(), 3);
  const int W = c.scene.width, half = c.cell / 4;
  for (size_t k = 0; k < c.ids.size(); ++k) {
    const int cx = static_cast<int>(k % c.columns) * c.cell + c.cell / 2;
    const int cy = static_cast<int>(k / c.columns) * c.cell + c.cell / 2;
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (int y = cy - half; y < cy + half; ++y)
      for (int x = cx - half; x < cx + half; ++x) {
        const size_t p = static_cast<size_t>(y) * W + x;
        const Vec3 v(XYZ[p * 3], XYZ[p * 3 + 1], XYZ[p * 3 + 2]);
        if (!v.allFinite()) continue;
        sum += v;
        ++n;
      }
    out.row(k) = (n ? Vec3(sum / n) : Vec3::Constant(NAN)).transpose();
  }
  return out;
}

/// Every pixel of the central half of each cell as a row (estimate, truth): per-pixel errors as
/// the paper's booth scenes (Tables 3-4) are evaluated.
inline void pixel_rows(const std::vector<float>& XYZ, const GridScene& c, PatchMatrix& est, PatchMatrix& truth) {
  std::vector<Vec3> e, t;
  const int W = c.scene.width, half = c.cell / 4;
  for (size_t k = 0; k < c.ids.size(); ++k) {
    const int cx = static_cast<int>(k % c.columns) * c.cell + c.cell / 2;
    const int cy = static_cast<int>(k / c.columns) * c.cell + c.cell / 2;
    for (int y = cy - half; y < cy + half; ++y)
      for (int x = cx - half; x < cx + half; ++x) {
        const size_t p = static_cast<size_t>(y) * W + x;
        e.push_back(Vec3(XYZ[p * 3], XYZ[p * 3 + 1], XYZ[p * 3 + 2]));
        t.push_back(c.XYZ[k]);
      }
  }
  est.resize(e.size(), 3);
  truth.resize(t.size(), 3);
  for (size_t i = 0; i < e.size(); ++i) {
    est.row(i) = e[i].transpose();
    truth.row(i) = t[i].transpose();
  }
}

inline PatchMatrix to_patch_matrix(const std::vector<Vec3>& v) {
  PatchMatrix m(v.size(), 3);
  for (size_t i = 0; i < v.size(); ++i) m.row(i) = v[i].transpose();
  return m;
}

}  // namespace tristim::test

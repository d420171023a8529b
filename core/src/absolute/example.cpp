// The worked example of the absolute chain on the virtual bracket camera (rules in
// tristim/absolute/example.hpp).
#include "tristim/absolute/example.hpp"

#include <algorithm>
#include <cmath>

#include "../detmath.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/absolute/stimuli_file.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/error.hpp"
#include "tristim/simulate/virtual_camera.hpp"

namespace tristim {

namespace {

double luminance_sum(const SpectralData& spectra, size_t k) {  // Σ ȳ·φ, up to one constant
  const SpectralData& cm = cmfs(Observer::CIE1931_2);
  const auto ybar = interpolate_spectrum(cm.wavelengths, cm.values[1], spectra.wavelengths);
  const auto phi = interpolate_spectrum(spectra.wavelengths, spectra.values[k], spectra.wavelengths, spectra.linear);
  double s = 0;
  for (size_t i = 0; i < ybar.size(); ++i) s += ybar[i] * phi[i];
  return s;
}

void add_column(SpectralData& to, const SpectralData& from, size_t k, const std::string& name) {
  const auto v = interpolate_spectrum(from.wavelengths, from.values[k], to.wavelengths, from.linear);
  to.values.push_back(v);
  to.names.push_back(name);
}


}  // namespace

// The ColorChecker SG patches whose reflectance differs from every ColorChecker Classic patch
// (spectral RMS difference > 0.03): training colours that are not the test colours.
SpectralData sg_unlike_classic() {
  const SpectralData sg = chart_reflectances("sg140"), cc = align_spectra(chart_reflectances("cc24"), sg.wavelengths);
  SpectralData keep;
  keep.wavelengths = sg.wavelengths;
  for (size_t k = 0; k < sg.size(); ++k) {
    double nearest = 1e9;
    for (const auto& c : cc.values) {
      double ss = 0;
      for (size_t i = 0; i < c.size(); ++i) ss += (c[i] - sg.values[k][i]) * (c[i] - sg.values[k][i]);
      nearest = std::min(nearest, std::sqrt(ss / c.size()));
    }
    if (nearest > 0.03) {
      keep.names.push_back(sg.names[k]);
      keep.values.push_back(sg.values[k]);
    }
  }
  return keep;
}

std::vector<ExampleChoice> example_light_table() {
  return {{"D65", "D65", "CIE daylight (the default)", ""},
          {"A", "A", "tungsten: projected colours leave a metameric floor with this camera", ""},
          {"F2", "F2", "cool-white fluorescent: projected colours leave a metameric floor with this camera", ""}};
}

// Projected colours (the paper's) leave a metameric floor under A and F2 for this camera;
// reflective colours under the scene's light with T2R meet Table 4 (tests/core/absolute/example_test.cpp).
std::vector<ExampleChoice> example_training_table() {
  return {{"projector", "24 projected ColorChecker colours (the paper's)",
           "the paper's training: three-primary projector light matched to the ColorChecker", ""},
          {"reflective", "reflective ColorChecker SG patches under the scene's light",
           "the SG patches unlike the Classic's, lit by the scene's light: meets Table 4 under A and F2 with T2R", "T2R"}};
}

AbsoluteExample make_absolute_example(const AbsoluteExampleOptions& o) {
  if (o.cell < 8) throw Error(ErrorCode::InvalidArgument, "example: cells need at least 8 pixels");
  if (!(o.white_luminance > 0)) throw Error(ErrorCode::InvalidArgument, "example: the white luminance must be positive");
  if (o.colour_training != "projector" && o.colour_training != "reflective")
    throw Error(ErrorCode::InvalidArgument, "example: colour training is 'projector' or 'reflective', not '" + o.colour_training + "'");
  const SpectralData light = illuminant_spd(o.illuminant);  // UnknownId for an illuminant that is not built in
  AbsoluteExample ex;
  ex.camera = o.camera;
  ex.sensor.ssf = camera_ssf(o.camera);
  ex.sensor.model = "Virtual " + o.camera;
  ex.sensor.oecf_exponent = {1.03, 1.0, 0.97};
  ex.bracket = {{1.0 / 250, 8, 100}, {1.0 / 125, 8, 100}, {1.0 / 60, 8, 100}, {1.0 / 30, 8, 100}, {1.0 / 15, 8, 100}};
  const ExposureSettings mid = ex.bracket[2];
  std::uint64_t seed = o.seed * 100000;

  // The scene: 24 ColorChecker patches under the light, then a 12-step ladder of equal-tristimulus light.
  const SpectralData refl = chart_reflectances("cc24");
  const SpectralData cc = reflected_spectra(refl, light);
  const SpectralData E = projector_spectra({Vec3(1, 1, 1)}, {"E"});
  size_t white = 0;
  for (size_t k = 1; k < cc.size(); ++k)
    if (luminance_sum(cc, k) > luminance_sum(cc, white)) white = k;
  VirtualScene scene;
  scene.stimuli.wavelengths = E.wavelengths;
  scene.stimuli.linear = true;
  std::vector<std::string> ids;
  for (size_t k = 0; k < cc.size(); ++k) {
    add_column(scene.stimuli, cc, k, cc.names[k]);
    scene.luminance.push_back(o.white_luminance * luminance_sum(cc, k) / luminance_sum(cc, white));
  }
  ex.white_id = cc.names[white];
  for (int k = 0; k < 12; ++k) {
    const double Y = 0.3 * detmath::pow(10.0, 4.0 * k / 11.0);
    char name[32];
    std::snprintf(name, sizeof name, "E%.3g", Y);
    add_column(scene.stimuli, E, 0, name);
    scene.luminance.push_back(Y);
  }
  const int columns = 6, rows = 6;
  scene.width = columns * o.cell;
  scene.height = rows * o.cell;
  scene.label.resize(static_cast<size_t>(scene.width) * scene.height);
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x)
      scene.label[static_cast<size_t>(y) * scene.width + x] = static_cast<std::uint16_t>((y / o.cell) * columns + x / o.cell);
  for (size_t k = 0; k < scene.stimuli.size(); ++k) {
    const int cx = static_cast<int>(k % columns) * o.cell, cy = static_cast<int>(k / columns) * o.cell;
    ex.regions.push_back({scene.stimuli.names[k], cx, cy, o.cell, o.cell, virtual_XYZ(ex.sensor, scene, static_cast<int>(k))});
  }
  for (size_t e = 0; e < ex.bracket.size(); ++e) {
    ex.frame_seeds.push_back(seed);
    ex.frames.push_back(capture_virtual(ex.sensor, scene, ex.bracket[e], seed++));
    ex.labels.push_back(ex.bracket[e].label());
    ex.frame_names.push_back("virtual-" + std::to_string(e + 1) + ".raw");
  }
  // The test scene: the cells as region rows of the middle frame (any frame of the bracket names
  // the same fused maps).
  std::vector<AbsoluteStimulus> test;
  for (const auto& g : ex.regions) {
    AbsoluteStimulus t;
    t.id = g.id, t.file = ex.frame_names[2], t.x = g.x, t.y = g.y, t.w = g.w, t.h = g.h, t.XYZ = g.XYZ;
    t.set = equal_tristimulus(g.XYZ) ? "luminance" : "colour";
    test.push_back(t);
  }
  ex.test_csv = absolute_stimuli_to_csv(test);

  // Calibration frames at the scene's size.
  const int W = scene.width, H = scene.height;
  ex.lens_cap_scene = uniform_scene(W, H, E, 0.0);
  ex.flat_scene = uniform_scene(W, H, E, 450.0);
  for (int i = 0; i < 4; ++i) {
    ex.lens_cap_seeds.push_back(seed);
    ex.lens_cap.push_back(capture_virtual(ex.sensor, ex.lens_cap_scene, mid, seed++));
    ex.lens_cap_names.push_back("virtual-cap-" + std::to_string(i + 1) + ".raw");
  }
  ex.flat_seed = seed;
  ex.flat = capture_virtual(ex.sensor, ex.flat_scene, mid, seed++);
  ex.flat_name = "virtual-flat.raw";
  ex.scene = scene;

  // Training stimuli, sampled at the centre with the normalisation the page will rebuild from
  // the same frames (n from the lens cap, f(r) from the flat; S and areas do not enter sampling).
  std::vector<const RawImage*> caps;
  for (const auto& c : ex.lens_cap) caps.push_back(&c);
  const DarkFrame cap = average_dark_frames(caps);
  SaturationEstimate sat;
  sat.level = sat.reported = {ex.sensor.saturation, ex.sensor.saturation, ex.sensor.saturation};
  sat.fraction = {1, 1, 1};
  const Normalisation n = make_normalisation(&cap, sat, &ex.sensor.ssf, fit_falloff_Guarnera2018(ex.flat, &cap), 10);
  const int rx = W / 2 - 4, ry = H / 2 - 4;
  auto keep = [&](const TrainingStimulus& s) {
    if (!s.saturated[0] && !s.saturated[1] && !s.saturated[2]) ex.stimuli.push_back(s);
  };
  std::vector<double> training_Y;  // 0, 30, …, 870, 890 cd/m² (the paper's luminance training set)
  for (int v = 0; v <= 870; v += 30) training_Y.push_back(v);
  training_Y.push_back(890);
  for (double Y : training_Y) {
    for (size_t e = 0; e < ex.bracket.size(); ++e) {
      const RawImage f = capture_virtual(ex.sensor, uniform_scene(W, H, E, Y), ex.bracket[e], seed++);
      keep(sample_stimulus(f, rx, ry, 8, 8, n, ex.bracket[e], Vec3(Y, Y, Y),
                           "Y" + std::to_string(static_cast<int>(Y)) + "@" + std::to_string(e + 1)));
    }
  }
  if (o.colour_training == "reflective") {
    // Reflective colours under the scene's light (ColorChecker SG patches unlike the Classic's),
    // the brightest at 700 cd/m², each photographed at the middle exposure.
    const SpectralData sg = reflected_spectra(sg_unlike_classic(), light);
    double top = 0;
    for (size_t k = 0; k < sg.size(); ++k) top = std::max(top, luminance_sum(sg, k));
    for (size_t k = 0; k < sg.size(); ++k) {
      keep(shoot_colour_stimulus(ex.sensor, sg, k, 700.0 * luminance_sum(sg, k) / top, W, H, mid, seed++, n,
                                 "colour SG " + sg.names[k]));
    }
    ex.stimuli_csv = stimuli_to_csv(ex.stimuli);
    return ex;
  }
  const ReferenceChart ref = reference_chart("cc24", "D65");
  std::vector<Vec3> targets;
  for (const auto& x : ref.XYZ) targets.push_back(x * 7.0);
  const SpectralData proj = projector_spectra(targets, ref.ids);
  for (size_t k = 0; k < targets.size(); ++k) {
    keep(shoot_colour_stimulus(ex.sensor, proj, k, targets[k][1], W, H, mid, seed++, n, "colour " + ref.ids[k]));
  }
  ex.stimuli_csv = stimuli_to_csv(ex.stimuli);
  return ex;
}

}  // namespace tristim

// Writes a virtual bracketed series as DNG files for the `tristim absolute` / `sensitivities`
// CLI checks and the example (examples/absolute): the virtual bracket camera (Canon EOS 5D
// Mark II sensitivities, power-law OECF, shot and read noise, fall-off, clipping below the
// metadata's white level) photographing
//   cap_1.dng, cap_2.dng       lens cap (Y = 0)
//   flat.dng                   equal-tristimulus projector light, 450 cd/m²
//   train_1..5.dng             a training chart: 31 equal-tristimulus patches 0-890 cd/m² and the
//                              24 ColorChecker colours (D65, white 700 cd/m²) made by the projector,
//                              at 1/250 … 1/15 s, f/8
//   scene_1..5.dng             a ColorChecker under D65 (white 600 cd/m²) on a grey ground, same bracket
//   nometa.dng                 scene_3 without exposure tags;  other.dng  the same scene from another body
//   stimuli.csv                the training stimuli (file, region, measured X, Y, Z in cd/m²)
//   nonmonotonic.csv           the same with two luminances swapped
//   scene_truth.csv            the scene's patches: id, centre x, y, X, Y, Z (cd/m²)
//   scene_test.csv             a test scene for `absolute evaluate`: the 24 patches as region rows of
//                              scene_3.dng (central 18 px) with their X, Y, Z, and 24 per-patch rows
//                              (the example's projected colours, R, G, B at 1/60 s f/8 ISO 100)
//   train_test.csv             the training chart's stimuli of 1/60 s as region rows (a test scene on
//                              the training bracket, as the page takes it: rows naming its files)
//   patches_rgb.csv            linear camera RGB of a ColorChecker under D65 (for `sensitivities estimate`)
//   example/                   the page's virtual-camera example (make_absolute_example, defaults) as
//                              files named as the page names its frames: virtual-1..5.raw (DNGs of the
//                              bracket, ISO 100), virtual-cap-1..4.raw, virtual-flat.raw, stimuli.csv,
//                              test.csv (the cells as region rows), recipe.json (the page's recipe:
//                              `absolute fit --recipe` reads it), white_id.txt, exposures.txt (the
//                              bracket's exposures to 17 digits: LibRaw keeps a DNG's as float)
// usage: absolute_fixture <output folder>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <sys/stat.h>

#include "absolute_training_chart.hpp"
#include "dng_writer.hpp"
#include "tristim/absolute/example.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/absolute/virtual_bracket.hpp"
#include "tristim/chart/reference.hpp"
#include "tristim/simulate/virtual_camera.hpp"

using namespace tristim;

namespace {

constexpr int W = 128, H = 112, kCols = 8, kCell = 16;
const char* kCamera = "Canon_EOS_5D_Mark_II";

void write(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
}

void dng(const std::string& path, const VirtualSensor& s, const VirtualScene& scene, const ExposureSettings& e,
         std::uint64_t seed, bool tags = true, int black = 0) {
  DngWriteOptions o;
  o.make = s.make;
  o.model = s.model;
  o.black = static_cast<std::uint16_t>(black);
  o.white = static_cast<std::uint32_t>(s.reported_saturation) + o.black;
  if (tags) {
    o.exposure_s = e.exposure_s;
    o.f_number = e.f_number;
    o.iso = static_cast<std::uint16_t>(e.iso);
  }
  write(path, write_dng(capture_virtual_mosaic(s, scene, e, seed, black), 2 * scene.width, 2 * scene.height, o));
}

std::string g17(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

/// The page's example as files (see the header comment); its colour stimuli for scene_test.csv.
std::vector<AbsoluteStimulus> write_example(const std::string& dir) {
  mkdir(dir.c_str(), 0755);
  const AbsoluteExample ex = make_absolute_example();
  // A black level of 64 DN keeps the read noise's values below 0 DN (lens cap): the files decode
  // to the example's frames exactly.
  for (size_t e = 0; e < ex.bracket.size(); ++e)
    dng(dir + ex.frame_names[e], ex.sensor, ex.scene, ex.bracket[e], ex.frame_seeds[e], true, 64);
  const ExposureSettings mid = ex.bracket[2];
  for (size_t i = 0; i < ex.lens_cap_names.size(); ++i)
    dng(dir + ex.lens_cap_names[i], ex.sensor, ex.lens_cap_scene, mid, ex.lens_cap_seeds[i], true, 64);
  dng(dir + ex.flat_name, ex.sensor, ex.flat_scene, mid, ex.flat_seed, true, 64);
  write_text(dir + "stimuli.csv", ex.stimuli_csv);
  write_text(dir + "test.csv", ex.test_csv);
  write_text(dir + "white_id.txt", ex.white_id + "\n");
  std::string exposures;
  for (const auto& e : ex.bracket) exposures += g17(e.exposure_s) + "," + g17(e.f_number) + "," + g17(e.iso) + "\n";
  write_text(dir + "exposures.txt", exposures);
  AbsoluteRecipe r;  // as the page makes it for the example
  r.inputs.stimuli = read_absolute_stimuli(ex.stimuli_csv, "example-stimuli.csv");
  r.inputs.bracket = ex.frame_names;
  r.inputs.lens_cap = ex.lens_cap_names;
  r.inputs.flat = ex.flat_name;
  r.inputs.sensitivities.choice = "camera";
  r.inputs.sensitivities.camera = ex.camera;
  write_text(dir + "recipe.json", absolute_recipe_to_json(r));
  std::vector<AbsoluteStimulus> colours;
  for (const auto& s : r.inputs.stimuli)
    if (s.set == "colour") colours.push_back(s);
  return colours;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: absolute_fixture <output folder>\n";
    return 2;
  }
  const std::string dir = std::string(argv[1]) + "/";
  mkdir(argv[1], 0755);
  try {
    VirtualSensor s;
    s.ssf = camera_ssf(kCamera);
    s.model = std::string("Virtual ") + kCamera;
    s.oecf_exponent = {1.03, 1.0, 0.97};
    const std::vector<ExposureSettings> bracket = {{1.0 / 250, 8, 0}, {1.0 / 125, 8, 0}, {1.0 / 60, 8, 0},
                                                   {1.0 / 30, 8, 0}, {1.0 / 15, 8, 0}};
    const SpectralData E = projector_spectra({Vec3(1, 1, 1)}, {"E"});
    dng(dir + "cap_1.dng", s, uniform_scene(W, H, E, 0), bracket[2], 1);
    dng(dir + "cap_2.dng", s, uniform_scene(W, H, E, 0), bracket[2], 2);
    dng(dir + "flat.dng", s, uniform_scene(W, H, E, 450), bracket[2], 3);

    // The training chart: 31 equal-tristimulus patches, then 24 projected ColorChecker colours.
    const test::TrainingChart training = test::training_chart(W, H, kCols, kCell);
    const VirtualScene& train = training.scene;
    const std::vector<std::string>& ids = training.ids;
    const int n = static_cast<int>(ids.size());
    std::ostringstream csv;
    csv << "id,set,file,x,y,w,h,X,Y,Z\n";
    for (size_t e = 0; e < bracket.size(); ++e) {
      const std::string file = "train_" + std::to_string(e + 1) + ".dng";
      dng(dir + file, s, train, bracket[e], 10 + e);
      for (int k = 0; k < n; ++k) {
        const bool colour = k >= 31;
        if (colour && e != 2) continue;  // colours: one shot at 1/60 s
        const Vec3 xyz = virtual_XYZ(s, train, k);
        csv << ids[k] << "@" << e + 1 << "," << (colour ? "colour" : "luminance") << "," << file << ","
            << (k % kCols) * kCell + 4 << "," << (k / kCols) * kCell + 4 << ",8,8," << xyz[0] << "," << xyz[1] << ","
            << xyz[2] << "\n";
      }
    }
    write_text(dir + "stimuli.csv", csv.str());
    {  // the stimuli of 1/60 s as a test scene on the training bracket
      std::istringstream rows(csv.str());
      std::string line, test = "id,set,file,x,y,w,h,X,Y,Z\n";
      std::getline(rows, line);
      while (std::getline(rows, line))
        if (line.find(",train_3.dng,") != std::string::npos) test += line.replace(line.find('@'), 2, "") + "\n";
      write_text(dir + "train_test.csv", test);
    }
    // Two stimuli of the middle exposure with their luminances swapped.
    std::string bad = csv.str();
    const std::string a = "Y150@3,luminance", b = "Y450@3,luminance";
    const auto pa = bad.find(a), pb = bad.find(b);
    const auto la = bad.find('\n', pa), lb = bad.find('\n', pb);
    std::string row_a = bad.substr(pa, la - pa), row_b = bad.substr(pb, lb - pb);
    const auto xyz_a = row_a.substr(row_a.find(",8,8,")), xyz_b = row_b.substr(row_b.find(",8,8,"));
    bad.replace(pb, lb - pb, row_b.substr(0, row_b.find(",8,8,")) + xyz_a);
    bad.replace(pa, la - pa, row_a.substr(0, row_a.find(",8,8,")) + xyz_b);
    write_text(dir + "nonmonotonic.csv", bad);

    // The scene: a ColorChecker under D65 (patches 18 px, 2 px gaps) on a 20 % grey ground.
    const SpectralData refl = chart_reflectances("cc24");
    SpectralData spectra = reflected_spectra(refl, illuminant_spd("D65"));
    const auto white = reflectances_to_XYZ(refl, illuminant_spd("D65"));
    VirtualScene scene;
    scene.width = W;
    scene.height = H;
    scene.stimuli = spectra;
    for (const auto& x : white) scene.luminance.push_back(600.0 * x[1] / white[18][1]);
    scene.stimuli.names.push_back("ground");
    scene.stimuli.values.push_back(spectra.values[18]);  // the white patch's spectrum at 20 %
    scene.luminance.push_back(0.2 * 600.0);
    scene.label.assign(static_cast<size_t>(W) * H, 24);
    const int ox = (W - 6 * 20) / 2, oy = (H - 4 * 20) / 2;
    std::ostringstream truth;
    truth << "id,x,y,X,Y,Z\n";
    for (int k = 0; k < 24; ++k) {
      const int x0 = ox + (k % 6) * 20 + 1, y0 = oy + (k / 6) * 20 + 1;
      for (int y = y0; y < y0 + 18; ++y)
        for (int x = x0; x < x0 + 18; ++x) scene.label[static_cast<size_t>(y) * W + x] = static_cast<std::uint16_t>(k);
      const Vec3 xyz = virtual_XYZ(s, scene, k);
      truth << refl.names[k] << "," << x0 + 9 << "," << y0 + 9 << "," << xyz[0] << "," << xyz[1] << "," << xyz[2] << "\n";
    }
    write_text(dir + "scene_truth.csv", truth.str());
    // The test scene: the patches as region rows (their 18 px), then the example's projected colours per patch.
    std::vector<AbsoluteStimulus> test;
    for (int k = 0; k < 24; ++k) {
      AbsoluteStimulus t;
      t.id = refl.names[k];
      t.file = "scene_3.dng";
      t.x = ox + (k % 6) * 20 + 1, t.y = oy + (k / 6) * 20 + 1, t.w = t.h = 18;
      t.XYZ = virtual_XYZ(s, scene, k);
      t.set = "colour";
      test.push_back(t);
    }
    for (const auto& c : write_example(dir + "example/")) test.push_back(c);
    write_text(dir + "scene_test.csv", absolute_stimuli_to_csv(test));
    for (size_t e = 0; e < bracket.size(); ++e)
      dng(dir + "scene_" + std::to_string(e + 1) + ".dng", s, scene, bracket[e], 100 + e);
    dng(dir + "nometa.dng", s, scene, bracket[2], 200, false);
    VirtualSensor other = s;
    other.model = "Another body";
    dng(dir + "other.dng", other, scene, bracket[2], 201);

    // Linear camera RGB of a ColorChecker under D65 (for sensitivities estimate).
    const auto rgb = simulate_camera_RGB(s.ssf, refl, illuminant_spd("D65"));
    std::ostringstream p;
    p << "patch,R,G,B\n";
    for (size_t k = 0; k < rgb.size(); ++k) p << refl.names[k] << "," << rgb[k][0] << "," << rgb[k][1] << "," << rgb[k][2] << "\n";
    write_text(dir + "patches_rgb.csv", p.str());
  } catch (const std::exception& e) {
    std::cerr << "absolute_fixture: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote the virtual bracket to " << dir << "\n";
  return 0;
}

// A worked example of the absolute tele-colorimeter made entirely with the virtual bracket camera
// (virtual_bracket.hpp), so the chain can be tried without a lab: everything Guarnera 2018
// section 4 photographs, generated.
//  * calibration: lens-cap frames (noise floor n, eq 7) and a flat field of equal-tristimulus
//    light (the radial fall-off f(r), eq 7), both at the scene's size;
//  * training stimuli, sampled per patch (centre of the frame): the luminance set (equal-
//    tristimulus projector light 0-890 cd/m² in 30 cd/m² steps at every exposure of the bracket)
//    and the colour set (the 24 ColorChecker colours projected, white 700 cd/m², at the middle
//    exposure — the paper's training; or, with colour_training "reflective", the ColorChecker SG
//    patches unlike the Classic's under the scene's light, brightest 700 cd/m²: with this camera
//    only such training meets Table 4 under A and F2, since projector light of three primaries
//    leaves a metameric floor above it); stimuli with a channel in the saturated zone are left
//    out, as a user would;
//  * the scene: a 6 × 6 grid of cells — rows 1-4 a ColorChecker under `illuminant` (white patch at
//    `white_luminance`), rows 5-6 a ladder of 12 equal-tristimulus cells from 0.3 to 3000 cd/m²
//    (four decades; log-spaced) — photographed at every exposure of the bracket
//    (1/250 … 1/15 s, f/8, ISO 100, one-stop steps);
//  * the truth: X, Y, Z of every cell (cd/m², the virtual camera's CIE 1931 integration).
// The sensor clips below what its metadata claims (S = 15000 DN, reported 16000), so S has to
// be measured from the data; its OECF exponents are 1.03, 1, 0.97.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tristim/absolute/virtual_bracket.hpp"
#include "tristim/absolute/luminance.hpp"

namespace tristim {

struct AbsoluteExampleOptions {
  std::string camera = "Canon_EOS_5D_Mark_II";  ///< built-in sensitivities (camera_names())
  int cell = 32;                 ///< cell size of the scene grid, measurement pixels (≥ 8)
  double white_luminance = 600;  ///< Y of the ColorChecker's white patch, cd/m²
  std::string illuminant = "D65";           ///< the light on the scene's ColorChecker (built-in id: D65, A, F2, …)
  std::string colour_training = "projector";  ///< "projector" (24 projected ColorChecker colours) | "reflective"
  std::uint64_t seed = 1;
};

/// One choice of the example's light or colour training as the page's pickers list it.
struct ExampleChoice {
  std::string id;     ///< AbsoluteExampleOptions::illuminant or ::colour_training
  std::string label;  ///< the picker's text
  std::string about;  ///< why it is offered
  /// The colour matrix (Guarnera2018-<transform>) that meets Table 4 with this training; "" when
  /// the chosen matrix is kept.
  std::string transform;
};
/// The lights the example offers on the scene's chart (the paper's booth lights), D65 first.
std::vector<ExampleChoice> example_light_table();
/// The example's colour trainings, the paper's (projector) first.
std::vector<ExampleChoice> example_training_table();

/// One cell of the scene and its truth.
struct ExampleRegion {
  std::string id;
  int x = 0, y = 0, w = 0, h = 0;  ///< the cell, measurement pixels
  Vec3 XYZ = Vec3::Zero();         ///< cd/m²
};

struct AbsoluteExample {
  VirtualSensor sensor;
  std::string camera;
  std::vector<ExposureSettings> bracket;    ///< shortest first
  std::vector<std::string> labels;          ///< the bracket's exposures as text ("1/250 s f/8 ISO 100")
  std::vector<RawImage> frames;             ///< the scene at each exposure of the bracket
  std::vector<RawImage> lens_cap;           ///< 4 lens-cap frames (middle exposure)
  RawImage flat;                            ///< equal-tristimulus light, ~450 cd/m², middle exposure
  std::vector<TrainingStimulus> stimuli;    ///< per patch (raw_RGB, falloff), unsaturated only
  std::vector<ExampleRegion> regions;       ///< the scene's cells with their X, Y, Z
  std::string white_id;                     ///< the ColorChecker's white patch (eq 16)
  /// The files the frames stand for, as a recipe names them ("virtual-1.raw" …, "virtual-cap-1.raw"
  /// …, "virtual-flat.raw"); tests write the frames under these names as DNGs.
  std::vector<std::string> frame_names, lens_cap_names;
  std::string flat_name;
  std::string stimuli_csv;                  ///< `stimuli` as a stimuli CSV (stimuli_to_csv)
  /// The test scene: every cell as a region row of the middle exposure's frame with its X, Y, Z
  /// (sets by the 2 % rule: the ladder's cells are equal-tristimulus), as a stimuli CSV.
  std::string test_csv;
  /// How each frame was made: capture_virtual_mosaic(sensor, scene, exposure, seed) gives its
  /// sensor values (a DNG of them decodes to the frame).
  VirtualScene scene, lens_cap_scene, flat_scene;
  std::vector<std::uint64_t> frame_seeds, lens_cap_seeds;
  std::uint64_t flat_seed = 0;
};

/// Generates the example. Error(UnknownId) for a camera or illuminant that is not built in;
/// InvalidArgument for a cell < 8 pixels, a non-positive white luminance or another colour training.
/// The ColorChecker SG patches whose reflectance differs from every ColorChecker Classic patch
/// (spectral RMS difference > 0.03): reflective training colours that are not the test colours.
SpectralData sg_unlike_classic();

AbsoluteExample make_absolute_example(const AbsoluteExampleOptions& options = {});

}  // namespace tristim

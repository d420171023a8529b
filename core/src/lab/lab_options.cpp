// The lab's option rows (tristim/lab/lab_options.hpp); render.cpp, exercises.cpp,
// exercises_abed.cpp and metamerism.cpp check their values with lab_option(), and
// tests/core/lab/lab_options_test.cpp holds each bound against the function it bounds.
#include "tristim/lab/lab_options.hpp"

#include <cmath>

#include "tristim/error.hpp"
#include "tristim/io/json.hpp"
#include "tristim/lab/exercises.hpp"
#include "tristim/lab/metamerism.hpp"
#include "tristim/lab/render.hpp"
#include "tristim/surface/options_table.hpp"
#include "../citations.hpp"

namespace tristim {

namespace {

OptionSpec row(const std::string& name, const std::string& label, double default_number, double min, double max,
               const std::string& unit, const std::string& description, const std::string& type = "number") {
  OptionSpec o = number_option(name, label, default_number, min, max, description, type);
  o.step = type == "integer" ? 1 : 0;
  o.unit = unit;
  return o;
}

// Exercise 4 runs the surface step's simulated Table IV (geometry_experiment_Abed2013): its noise
// row, named for `lab table4`, so the bound is the one that function enforces.
OptionSpec table4_noise() {
  for (OptionSpec o : surface_option_table())
    if (o.name == "noise") {
      o.name = "table4.noise";
      o.default_number = kTable4Noise;
      o.description = "exercise 4: " + o.description;
      return o;
    }
  throw Error(ErrorCode::Internal, "surface_option_table has no noise row");
}

}  // namespace

std::vector<OptionSpec> lab_option_table() {
  const LabRenderOptions render;
  const OverfitOptions overfit;
  const MetamerOptions metamers;
  // A seed is a whole number a double (and the page's number box) holds exactly.
  constexpr double kSeedMax = 999999999999999;
  return {
      row("render.exposure", "Exposure", render.exposure, 1e-6, 4, "white's G / saturation",
          "e: the white diffuser's G as a fraction of the sensor's saturation (above 1 it clips)"),
      row("render.shot_gain", "Shot-noise gain", render.shot_gain, 0, 1000, "variance per DN",
          "g: shot-noise variance per DN, variance = g·DN + read² per sensor pixel (--noise g,read)"),
      row("render.read_noise", "Read noise", render.read_noise, 0, 10000, "DN",
          "σ_r: read noise per sensor pixel (--noise g,read)"),
      row("render.falloff", "Fall-off", render.falloff, 0, 0.9, "a",
          "light fall-off 1 − a·r², r = 1 at the image corners (Guarnera et al. 2018 eq 7's quadratic term)"),
      row("render.flare", "Flare", render.flare, 0, 1, "fraction of the white",
          "φ: a veil of this fraction of the white diffuser's response over the whole image"),
      row("render.seed", "Noise seed", static_cast<double>(render.seed), 0, kSeedMax, "",
          "the noise's seed: the same seed gives the same file in every build", "integer"),
      row("overfit.noise", "Noise", overfit.noise, 0, 0.5, "fraction of the white's G",
          "exercise 2: σ of the Gaussian camera noise on the training charts"),
      table4_noise(),
      row("metamers.max_match", "Largest ΔE00 under the first light", metamers.max_match, 0.01, 10, "",
          "search: a pair matches when its ΔE00 under the first light is below this"),
      row("metamers.top", "Pairs shown", metamers.top, 1, 1000000, "",
          "search: at most this many pairs, those that differ most under the second light", "integer"),
  };
}

std::vector<LabFileKind> lab_file_kinds() {
  const std::string quality = std::to_string(LabRenderOptions{}.jpeg_quality);
  return {{"dng", "DNG (linear RAW)", "dng", "image/x-adobe-dng", false},
          {"tiff", "TIFF, 16 bits through the OECF", "tiff", "image/tiff", true},
          {"jpeg", "JPEG, 8 bits through the OECF (quality " + quality + ")", "jpg", "image/jpeg", true}};
}

std::vector<MethodInfo> metamer_match_table() {
  return {{"observer", "the observer", "CIE XYZ under each light (CIE 15), CIELAB, ΔE00 (Sharma, Wu & Dalal 2005)", {}},
          {"camera", "the camera",
           "the virtual camera's RGB through its ISO 17321-1 matrix fitted under each light, CIELAB, ΔE00", {}}};
}

std::vector<MethodInfo> shen_training_table() {
  const std::string shen = citation::kShen2008;
  return {{"cc24", "ColorChecker Classic (the paper's MCC, 18 non-grey)",
           shen + ": the Macbeth ColorChecker, its greys D1-D6 left out of the fits", {}},
          {"sg140", "ColorChecker SG (140, in the CDC's role)",
           shen + ": the ColorChecker DC's role, a chart of many patches (the SG's 140 here)", {}}};
}

std::string lab_option_number(const OptionSpec& o, double value) {
  return o.type == "integer" ? json::number_text(value) : lab_number(value);
}

double lab_option(const std::string& name, double value) {
  for (const OptionSpec& o : lab_option_table()) {
    if (o.name != name) continue;
    const bool whole = o.type != "integer" || std::floor(value) == value;
    if (!(value >= o.min && value <= o.max) || !whole)
      throw Error(ErrorCode::InvalidArgument, "lab " + name.substr(0, name.find('.')) + ": " + name.substr(name.find('.') + 1) +
                                                  " (" + o.label + ") must be " +
                                                  (o.type == "integer" ? "a whole number " : "") + "in [" +
                                                  lab_option_number(o, o.min) + ", " + lab_option_number(o, o.max) + "], got " +
                                                  lab_option_number(o, value));
    return value;
  }
  throw Error(ErrorCode::Internal, "lab_option: no option '" + name + "'");
}

}  // namespace tristim

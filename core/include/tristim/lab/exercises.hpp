// tristim — the colorimetry lab's exercises, computed in the core so the page, the CLI
// (`tristim lab overfit`) and the tests print the same numbers.
//
// Exercise 2, "why a 3×3 is not enough": a camera (or the CMFs themselves, the Luther camera)
// photographs a training chart through the virtual camera (simulate/virtual_camera.hpp) with
// seeded Gaussian noise σ (relative to the white diffuser's G = 1); each model is fitted by least
// squares to the chart's reference XYZ and scored by mean CIEDE2000 on (a) the training patches,
// (b) leave-one-out (each patch predicted by the model fitted without it) and (c) a held-out
// set, the 1269 Munsell matte chips, noise-free. A model with more terms than the chart has
// patches is refused (TOO_FEW_PATCHES: infinitely many exact fits); with as many terms as
// patches the training error is ~0 and says nothing, which (b) and (c) show.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/io/json.hpp"

namespace tristim {

struct OverfitRow {
  std::string model;          ///< model id (model_table)
  std::string training;       ///< training chart id ("cc24", "sg140")
  int terms = 0;
  int patches = 0;            ///< training patches
  bool ok = false;            ///< false: refused (error_code, message)
  std::string error_code, message;
  /// Means; NaN when refused, loo also when N − 1 patches are too few for the model.
  double train_dE00 = std::numeric_limits<double>::quiet_NaN(), loo_dE00 = std::numeric_limits<double>::quiet_NaN(),
         test_dE00 = std::numeric_limits<double>::quiet_NaN();
};
/// {"model","training","terms","patches","ok","error_code","train_dE00","loo_dE00","test_dE00"}
/// (NaN as null).
json::Value overfit_row_json(const OverfitRow& row);

struct OverfitOptions {
  std::vector<std::string> models{"matrix-3x3", "Finlayson2015-2", "Cheung2004-10", "Cheung2004-22", "Cheung2004-35"};
  std::vector<std::string> training{"cc24", "sg140"};
  double noise = 0.002;       ///< σ of the camera noise, fraction of the white's G
  std::uint64_t seed = 1;
};

/// Every model × training chart (see header). Error(UnknownId) for an unknown model or chart.
std::vector<OverfitRow> lab_overfit_exercise(const SpectralData& sensitivities, const SpectralData& illuminant,
                                             const OverfitOptions& options = {});

// Exercise 1, "spectra to colour": one patch's reflectance R(λ), the colour stimulus R(λ)·S(λ)
// under each illuminant (each S scaled to 100 at 560 nm), and its XYZ (CIE 15 integration,
// Y_white = 100), CIELAB (relative to that illuminant's white: the von Kries-type normalisation
// CIELAB builds in) and xy per illuminant × observer — what `tristim reference --chart <c>
// --illuminant <I> --observer <O>` prints for that patch.
struct ColourRow {
  std::string illuminant, observer;
  Vec3 XYZ = Vec3::Zero(), Lab = Vec3::Zero();
  double x = 0, y = 0;
};
struct SpectraToColour {
  std::string chart, patch;
  std::vector<double> wavelengths;
  std::vector<double> reflectance;
  std::vector<std::vector<double>> stimulus;  ///< one per illuminant, in the order given
  std::vector<std::string> illuminants;
  std::vector<ColourRow> rows;                ///< illuminant-major, then observer
};
/// Error(UnknownId) for an unknown chart, patch, illuminant or observer.
SpectraToColour lab_spectra_to_colour(const std::string& chart, const std::string& patch,
                                      const std::vector<std::string>& illuminants = {"D65", "A", "F11"},
                                      const std::vector<std::string>& observers = {"1931", "1964"});

/// The CIE 1931 colour-matching functions as R, G, B sensitivities on 380-780 nm at 5 nm (the
/// built-in cameras' grid): a camera that meets the Luther condition.
SpectralData cmf_sensitivities();

}  // namespace tristim

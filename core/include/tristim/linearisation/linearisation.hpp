// Linearisation: the camera's inverse OECF per channel, from stored values (RAW, or non-linear
// TIFF/PNG/JPEG) to values proportional to exposure. One table row per method; the recipe's
// `linearisation` stage names a row by id. RAW data are linear already: `identity`.
//
// Shapes: PatchMatrix N × 3 (R, G, B), one row per patch, in the units the file stores
// (DN for RAW, 0..255 for 8-bit, 0..65535 for 16-bit).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/methods.hpp"

namespace tristim {

/// What a method may fit from. Everything but camera_RGB is optional (empty when absent).
struct LinearisationData {
  std::vector<std::string> ids;   ///< patch ids, one per row
  PatchMatrix camera_RGB;         ///< stored (non-linear) values, N × 3
  PatchMatrix reference_XYZ;      ///< known XYZ of the patches (0 rows when absent)
  SpectralData reflectances;      ///< known reflectances, columns named like `ids` (empty when absent)
  double full_scale = 0;          ///< the largest value the encoding can hold (255, 65535); 0: max of the data
};

/// A fitted linearisation: enough to apply it.
struct Linearisation {
  MethodChoice choice;                           ///< method id and its (completed) options
  std::array<std::vector<double>, 3> coefficients;  ///< per channel; meaning depends on the method
  double full_scale = 1;                         ///< input scale the coefficients refer to
  Vec3 r_squared = Vec3::Ones();                 ///< per-channel goodness of fit (1 when not fitted)
  std::vector<std::string> greys;                ///< patches a grey-based method used
  bool monotonic = true;                         ///< false: the curve is not monotonic over the data
  std::string message;                           ///< warnings, empty when none
};

/// One row of the linearisation table.
struct LinearisationMethod {
  MethodInfo info;
  /// Fits from data with the (completed) options.
  Linearisation (*fit)(const LinearisationData& data, const MethodChoice& choice);
  /// Stored value of one channel (0, 1, 2) -> linear value.
  double (*apply)(const Linearisation& fitted, int channel, double value);
};

/// Every linearisation method, in a stable order (`identity` first).
const std::vector<LinearisationMethod>& linearisation_table();
/// A row by id; Error(UnknownId) naming the id otherwise.
const LinearisationMethod& linearisation_method(const std::string& id);
/// Fits the chosen method (options checked and completed from the table).
Linearisation fit_linearisation(const MethodChoice& choice, const LinearisationData& data);
/// Applies a fitted linearisation to every row.
PatchMatrix linearise(const Linearisation& fitted, const PatchMatrix& camera_RGB);

}  // namespace tristim

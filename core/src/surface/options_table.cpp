// The surface step's number rows (bounds as fit_surface() and geometry_experiment_Abed2013()
// check them: tests/core/surface/options_table_test.cpp holds the two together).
#include "tristim/surface/options_table.hpp"

#include <string>

namespace tristim {

namespace {

OptionSpec row(const char* name, const char* label, double def, double lo, double hi, double step, const char* unit,
               const char* about) {
  OptionSpec o = number_option(name, label, def, lo, hi, about);
  o.step = step;
  o.unit = unit;
  return o;
}

}  // namespace

std::vector<OptionSpec> surface_option_table() {
  return {
      row("range_min", "from λ", 400, kSurfaceWavelengthMin, kSurfaceWavelengthMax, 10, "nm",
          "Phase I: the first wavelength of the fitted range (the CLI's --range "
          "omitted: the overlap of the two sets)"),
      row("range_max", "to λ", 700, kSurfaceWavelengthMin, kSurfaceWavelengthMax, 10, "nm",
          "Phase I: the last wavelength of the fitted range (at least the first)"),
      row("noise", "Noise σ", 0.001, 0, kSurfaceNoiseMax, 0.001, "white G = 1",
          "simulated Table IV: the virtual camera's noise standard deviation, relative to the perfect diffuser's G"),
  };
}

void check_surface_option(const std::string& name, double value) {
  // The rows' own check (complete_choice: finite, inside [min, max], the option named).
  complete_choice({"surface", "the surface step's numbers", "", surface_option_table()}, {"surface", {{name, value}}, {}});
}

}  // namespace tristim

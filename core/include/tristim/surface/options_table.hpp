// The bounds of the numbers a user gives the surface step (Abed, Berns & Masaoka 2013): the
// wavelength range a Phase I fit runs over (SurfaceFitOptions::range_min / range_max) and the
// noise σ of the simulated Table IV (geometry_experiment_Abed2013) — one OptionSpec row each, which
// the page builds its inputs from (labels, units, min/max/step/default) and `tristim surface
// --help` lists. fit_surface() and geometry_experiment_Abed2013() refuse a value outside its row
// with Error(InvalidArgument) naming the option.
#pragma once
#include <vector>

#include "tristim/methods.hpp"

namespace tristim {

/// A Phase I range's ends, in nm: the CIE tables' 360-830 nm and the 300 nm some
/// spectrophotometers start at (a fit may run outside the colorimetric range).
constexpr double kSurfaceWavelengthMin = 300, kSurfaceWavelengthMax = 830;
/// The largest noise σ of the simulated Table IV (white G = 1): 5 % of the white.
constexpr double kSurfaceNoiseMax = 0.05;

/// Rows named as the members they bound: range_min, range_max (nm), noise (σ, white G = 1).
std::vector<OptionSpec> surface_option_table();

/// Error(InvalidArgument) naming `name` when `value` lies outside row `name` of
/// surface_option_table() (or is not finite).
void check_surface_option(const std::string& name, double value);

}  // namespace tristim

// The bounds of the numbers a user gives the Jiang et al. 2013 estimate of a camera's sensitivities
// (absolute/sensitivities.hpp, the Absolute mode's eq 7 areas): SensitivityOptions' components K
// and smoothness — one OptionSpec row each, which the page builds its inputs from (labels, units,
// min/max/step/default) and `tristim absolute --help` lists. The recipe's own options (transform,
// fusion, w, noise floor, saturation) are absolute_option_table() (absolute/recipe.hpp).
#pragma once
#include <vector>

#include "tristim/absolute/sensitivities.hpp"
#include "tristim/methods.hpp"

namespace tristim {

/// Rows named as SensitivityOptions' members: components (integer), smoothness; defaults are
/// SensitivityOptions{}'s.
std::vector<OptionSpec> sensitivity_option_table();

/// Error(InvalidArgument) naming the option when `options`' components or smoothness lies outside
/// its row of sensitivity_option_table() (estimate_sensitivities_Jiang2013 calls it).
void check_sensitivity_options(const SensitivityOptions& options);

}  // namespace tristim

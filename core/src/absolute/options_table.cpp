// The sensitivity estimate's number rows (bounds as estimate_sensitivities_Jiang2013 checks them:
// tests/core/absolute/options_table_test.cpp holds the two together).
#include "tristim/absolute/options_table.hpp"

namespace tristim {

std::vector<OptionSpec> sensitivity_option_table() {
  const SensitivityOptions d;
  OptionSpec k = number_option("components", "Principal components K", d.components, 1, 12,
                               "per channel: the first K principal components of the built-in cameras' curves span the "
                               "estimate (Jiang et al. 2013: the space is low-dimensional); at most the number of patches",
                               "integer");
  k.step = 1;
  OptionSpec mu = number_option("smoothness", "Smoothness μ", d.smoothness, 0, 1,
                                "weight of the second-difference penalty relative to the data term (0: none; 1: as "
                                "heavy as the patches)");
  return {k, mu};
}

void check_sensitivity_options(const SensitivityOptions& o) {
  // The rows' own check (complete_choice: finite, integer K, inside [min, max], the option named).
  complete_choice({"sensitivities", "the sensitivity estimate's numbers", "", sensitivity_option_table()},
                  {"sensitivities", {{"components", o.components}, {"smoothness", o.smoothness}}, {}});
}

}  // namespace tristim

// Absolute recipe JSON (absolute/recipe.hpp, Guarnera 2018 mode): the strict reader with its
// completion, and the writer, which must give back a recipe that reads to the same text (a
// round-trip failure is a finding, not a refusal). Seeds: corpus/absolute_recipe/ (recipes the CLI
// wrote for the virtual bracket, cut to a few stimuli: region rows and per-patch rows).
#include "fuzz_support.hpp"
#include "tristim/absolute/recipe.hpp"

TRISTIM_FUZZ_TARGET({
  tristim::fuzz::round_trip(
      input, [](const std::string& t) { return tristim::absolute_recipe_from_json(t); },
      [](const tristim::AbsoluteRecipe& r) { return tristim::absolute_recipe_to_json(r); });
})

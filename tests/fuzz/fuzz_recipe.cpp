// Recipe JSON (profile/recipe.hpp): the strict reader, completion against the method tables, and
// the writer, which must give back a recipe that reads to the same text (a round-trip failure is a
// finding, not a refusal). Seeds: corpus/recipe/ (examples/recipes and variants).
#include "fuzz_support.hpp"
#include "tristim/profile/recipe.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::Recipe read = tristim::fuzz::round_trip(
      input, [](const std::string& t) { return tristim::recipe_from_json(t); },
      [](const tristim::Recipe& r) { return tristim::recipe_to_json(r); });
  tristim::recipe_to_json(tristim::complete_recipe(read));
})

// Recipe JSON (profile/recipe.hpp): the strict reader, completion against the method tables, and
// the writer, which must give back a recipe that reads to the same text (a round-trip failure is a
// finding, not a refusal). Seeds: corpus/recipe/ (examples/recipes and variants).
#include <cstdlib>

#include "fuzz_support.hpp"
#include "tristim/profile/recipe.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::Recipe read = tristim::recipe_from_json(input);
  const std::string text = tristim::recipe_to_json(read);
  std::string again;
  try {
    again = tristim::recipe_to_json(tristim::recipe_from_json(text));
  } catch (const tristim::Error&) {
    std::abort();  // what the writer wrote, the reader must read
  }
  if (again != text) std::abort();
  tristim::recipe_to_json(tristim::complete_recipe(read));
})

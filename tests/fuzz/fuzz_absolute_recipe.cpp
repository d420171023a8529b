// Absolute recipe JSON (absolute/recipe.hpp, Guarnera 2018 mode): the strict reader with its
// completion, and the writer, which must give back a recipe that reads to the same text (a
// round-trip failure is a finding, not a refusal). Seeds: corpus/absolute_recipe/ (recipes the CLI
// wrote for the virtual bracket, cut to a few stimuli: region rows and per-patch rows).
#include <cstdlib>

#include "fuzz_support.hpp"
#include "tristim/absolute/recipe.hpp"

TRISTIM_FUZZ_TARGET({
  const tristim::AbsoluteRecipe read = tristim::absolute_recipe_from_json(input);
  const std::string text = tristim::absolute_recipe_to_json(read);
  std::string again;
  try {
    again = tristim::absolute_recipe_to_json(tristim::absolute_recipe_from_json(text));
  } catch (const tristim::Error&) {
    std::abort();  // what the writer wrote, the reader must read
  }
  if (again != text) std::abort();
})

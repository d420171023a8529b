// CLI: `tristim models` — the characterisation model table, and the tables of the numbers and
// toggles the page builds its chart step from: the custom grid's and the sampled area's bounds
// (layout_option_table) and the sample flags a recipe may leave out (sample_flag_table). The
// page's catalog call reads the same rows. (fit: cmd_fit.cpp; evaluate, compare, apply, export:
// cmd_evaluate.cpp, cmd_compare.cpp, cmd_apply.cpp, cmd_export.cpp.)
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/chart/layout_options_table.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/io/json.hpp"
#include "tristim/profile/recipe.hpp"

namespace tristim::cli {


namespace {

int run_models(const Args& args, std::ostream& out) {
  args.allow_only({"json"});
  if (args.has("json")) {
    // The rows by their field lists (methods.hpp, models.hpp): what the page's catalog call gives.
    out << fields::object({{"models", fields::write(model_table())},
                           {"layout_options", fields::write(layout_option_table())},
                           {"sample_flags", fields::write(sample_flag_table())},
                           {"families", fields::write(model_families())}})
               .dump(2)
        << "\n";
    return 0;
  }
  for (const auto& m : model_table())
    out << std::left << std::setw(18) << m.id << std::setw(4) << m.n_terms << m.label << " — " << m.reference
        << (m.duplicate_of.empty() ? "" : " (same as " + m.duplicate_of + ")") << "\n";
  out << "\n" << option_rows_help("Custom grid and sampled area (tristim sample; the recipe's sampling.layout and area)",
                                  layout_option_table());
  out << "\n" << option_rows_help("Sample flags a recipe may leave out (sampling.exclude_flags; default 1: left out)",
                                  sample_flag_table());
  return 0;
}

const CommandRegistration reg_models({"models",
                                      "list the characterisation models, the chart grid's bounds and the sample flags",
                                      "tristim models [--json]\n"
                                      "  --json: {\"models\": [...], \"layout_options\": [...], \"sample_flags\": [...], \"families\": [...]}\n"
                                      "  (the rows the page's catalog has: a model's terms, an option's bounds)",
                                      run_models});

}  // namespace
}  // namespace tristim::cli

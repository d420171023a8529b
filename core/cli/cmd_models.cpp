// CLI: `tristim models` — the characterisation model table (fit: cmd_fit.cpp; evaluate, compare, apply,
// export: cmd_evaluate.cpp, cmd_compare.cpp, cmd_apply.cpp, cmd_export.cpp).
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/io/json.hpp"

namespace tristim::cli {
namespace {
int run_models(const Args& args, std::ostream& out) {
  args.allow_only({"json"});
  if (args.has("json")) {
    json::Value a = json::Value::array();
    for (const auto& m : model_table()) {
      json::Value o = json::Value::object();
      o.set("id", m.id);
      o.set("label", m.label);
      o.set("reference", m.reference);
      o.set("n_terms", m.n_terms);
      o.set("duplicate_of", m.duplicate_of);
      o.set("family", m.family);
      a.push(o);
    }
    out << a.dump(2) << "\n";
    return 0;
  }
  for (const auto& m : model_table())
    out << std::left << std::setw(18) << m.id << std::setw(4) << m.n_terms << m.label << " — " << m.reference
        << (m.duplicate_of.empty() ? "" : " (same as " + m.duplicate_of + ")") << "\n";
  return 0;
}

const CommandRegistration reg_models({"models", "list the characterisation models", "tristim models [--json]", run_models});

}  // namespace
}  // namespace tristim::cli

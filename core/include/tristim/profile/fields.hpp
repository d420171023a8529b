// Field lists (io/fields.hpp) of the small structs several documents share: a method choice here,
// the error summaries in evaluation/evaluation.hpp. One declaration each, so a recipe, a profile,
// a report and the CLI's JSON write them alike.
#pragma once
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/io/fields.hpp"
#include "tristim/methods.hpp"

namespace tristim::fields {

/// A method's options: numbers, and booleans read as 1 / 0.
inline void read_parameters(const json::Value& v, MethodChoice& c, const Context& ctx, const std::string& path) {
  if (!v.is_object()) ctx.refuse("'" + path + "' must be an object");
  for (const auto& [name, x] : v.members()) {
    if (x.is_bool()) c.parameters[name] = x.as_bool() ? 1 : 0;
    else Codec<double>::read(x, c.parameters[name], ctx, join(path, name));
  }
}
inline json::Value parameters_json(const MethodChoice& c) { return write(c.parameters); }

TRISTIM_FIELDS(MethodChoice, member<&MethodChoice::method>("method"),
               Field<MethodChoice>{"parameters", parameters_json, read_parameters, nullptr, false},
               member<&MethodChoice::settings>("settings", false));

}  // namespace tristim::fields

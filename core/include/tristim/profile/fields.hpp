// Field lists (io/fields.hpp) of the small structs several documents share: a method choice and
// an error summary. One declaration each, so a recipe, a profile, a report and the CLI's JSON
// write them alike.
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

TRISTIM_FIELDS(Summary, member<&Summary::min>("min"), member<&Summary::median>("median"), member<&Summary::mean>("mean"),
               member<&Summary::p95>("p95"), member<&Summary::max>("max"), member<&Summary::rms>("rms"),
               member<&Summary::std>("std"));

/// Per-patch errors (written beside their ids by metrics_json with per_patch).
TRISTIM_FIELDS(PatchErrors, member<&PatchErrors::dE76>("dE76"), member<&PatchErrors::dE94>("dE94"),
               member<&PatchErrors::dE00>("dE00"), member<&PatchErrors::dL>("dL"), member<&PatchErrors::dC>("dC"),
               member<&PatchErrors::dH>("dH"), member<&PatchErrors::dE_xyz>("dE_xyz"), member<&PatchErrors::rel_Y>("rel_Y"));

/// The summaries of Metrics (the per-patch errors are written apart, with the ids).
TRISTIM_FIELDS(Metrics, member<&Metrics::dE76>("dE76"), member<&Metrics::dE94>("dE94"), member<&Metrics::dE00>("dE00"),
               member<&Metrics::dE_xyz>("dE_xyz"), member<&Metrics::abs_rel_Y>("abs_rel_Y"),
               member<&Metrics::NRMSE>("NRMSE"));

}  // namespace tristim::fields

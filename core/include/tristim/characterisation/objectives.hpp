// The objectives table: how a model's coefficients are chosen. Each row's options are the
// fields of PatternSearchOptions / DeltaE2000Options (fit.hpp) with those structs' defaults,
// so the page's forms, the CLI and the recipe all read one source.
#pragma once
#include <string>
#include <vector>

#include "tristim/characterisation/fit.hpp"
#include "tristim/methods.hpp"

namespace tristim {

struct ObjectiveMethod {
  MethodInfo info;
  Objective objective;
};

/// ls, psm, de2000 — in that order.
const std::vector<ObjectiveMethod>& objective_table();
/// A row by id (also the aliases objective_from_id accepts); Error(UnknownId) otherwise.
const ObjectiveMethod& objective_method(const std::string& id);

/// The options of `choice` (completed from the table) written into `options`' psm / de2000
/// structs and objective. Error(UnknownId) / Error(InvalidArgument) as complete_choice.
void apply_objective_choice(const MethodChoice& choice, FitOptions& options);
/// The choice that reproduces options.objective with its psm / de2000 settings.
MethodChoice objective_choice(const FitOptions& options);
/// How a fit with `choice` reads in results: the row's label, and for CIEDE2000 (one row, two
/// losses, several optimisers) the loss and the optimiser the choice runs, e.g. "CIEDE2000 mean
/// (reweighted Levenberg-Marquardt)". Error(UnknownId) / Error(InvalidArgument) as complete_choice.
std::string objective_choice_label(const MethodChoice& choice);

}  // namespace tristim

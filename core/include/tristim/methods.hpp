// The shape every pluggable stage's method table shares (colour-science's
// MATRIX_COLOUR_CORRECTION_METHODS idea): one row per method with its id, label, the paper it
// comes from and the schema of its options. The page builds every picker and options form from
// these rows; the CLI's --help lists them; a recipe names a row by id and gives option values.
//
// Stages with a table: characterisation objectives (characterisation/objectives.hpp),
// linearisation (linearisation/linearisation.hpp), surface correction (surface/surface.hpp).
// Models have their own richer row (ModelInfo, characterisation/models.hpp).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "tristim/io/fields.hpp"

namespace tristim {

/// One option of a method. `type` is "number", "integer", "boolean" (0/1 in the parameters
/// map), "choice" (one of `choices`, in the settings map) or "text" (settings map).
struct OptionSpec {
  std::string name;         ///< key in MethodChoice::parameters / settings, snake_case
  std::string type;         ///< "number" | "integer" | "boolean" | "choice" | "text"
  std::string label;        ///< short human label for forms
  double default_number = 0;      ///< number / integer / boolean
  std::string default_text;       ///< choice / text
  double min = 0, max = 0;        ///< bounds of number/integer, inclusive unless min_exclusive (min == max: unbounded)
  std::vector<std::string> choices;
  std::string description;  ///< one sentence: what it does, units
  double step = 0;          ///< a form's increment for number options (0: any value; integers step 1)
  std::string unit = {};    ///< the unit a form shows after the label ("" when none, or in the label)
  bool min_exclusive = false;  ///< min itself is refused (value > min): a bound where the method degenerates
};

/// One row of a stage's method table.
struct MethodInfo {
  std::string id;         ///< the same string in C++, JS, files and the UI
  std::string label;      ///< human-readable
  std::string reference;  ///< the paper and equation(s) (core/src/citations.hpp: one spelling per
                          ///< work), or for a trivial method why it needs none; never empty: the
                          ///< CLI's --help and the page show it, and nothing else cites the method
  std::vector<OptionSpec> options;
};

/// A method chosen for a stage, with its option values (what a recipe stores). Options not
/// given take the table's defaults; options the method does not have are refused.
struct MethodChoice {
  std::string method;
  std::map<std::string, double> parameters;    ///< number / integer / boolean options
  std::map<std::string, std::string> settings; ///< choice / text options
};

/// An option row of type "number" (or "integer" / "boolean"): default and inclusive bounds.
OptionSpec number_option(const std::string& name, const std::string& label, double default_number, double min,
                         double max, const std::string& description, const std::string& type = "number");
/// An option row of type "text" (or "choice", with its `choices`): default text.
OptionSpec text_option(const std::string& name, const std::string& label, const std::string& description,
                       const std::string& default_text = "", const std::vector<std::string>& choices = {});

/// The MethodInfo of every row of a stage's table (rows with an `info` member).
template <class Row>
std::vector<MethodInfo> method_infos(const std::vector<Row>& rows) {
  std::vector<MethodInfo> out;
  for (const auto& r : rows) out.push_back(r.info);
  return out;
}

/// The ids of `rows` joined by `separator` (a message naming what a field takes).
std::string ids_of(const std::vector<MethodInfo>& rows, const std::string& separator = ", ");
/// Whether one of `rows` has this id.
bool has_id(const std::vector<MethodInfo>& rows, const std::string& id);

/// Checks `choice` against `info` (Error(UnknownId) for an option the method lacks,
/// Error(InvalidArgument) for a value of the wrong kind or out of bounds) and returns it with
/// every missing option filled with its default.
MethodChoice complete_choice(const MethodInfo& info, const MethodChoice& choice);

/// The value of a number/integer/boolean option (after complete_choice, always present).
double choice_number(const MethodChoice& choice, const std::string& name);
/// The value of a choice/text option.
const std::string& choice_text(const MethodChoice& choice, const std::string& name);

/// Parses "id" or "id:name=value,name=value" (the CLI's --linearisation / --surface syntax);
/// values that parse as numbers go to parameters, others to settings.
MethodChoice parse_choice(const std::string& text);

struct LinearisationListing;  // linearisation/linearisation.hpp

}  // namespace tristim

// Field lists (io/fields.hpp), defined in methods.cpp: the catalog's rows are the objects their JSON
// is, in their C++ names and order — what `tristim models --json`, `tristim linearise --list` print
// and the page's catalog call gives (a bound that is not a number: null). A LinearisationListing
// (a linearisation row with what it needs) is declared here so every stage's listing has its list
// beside OptionSpec's.
namespace tristim::fields {
TRISTIM_FIELDS_DECLARE(OptionSpec);
TRISTIM_FIELDS_DECLARE(MethodInfo);
TRISTIM_FIELDS_DECLARE(LinearisationListing);
}  // namespace tristim::fields

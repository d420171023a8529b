// Method-table options: defaults, checks and the CLI's "id:name=value,..." syntax.
#include "tristim/methods.hpp"

#include <cmath>
#include <cstdlib>

#include "tristim/characterisation/models.hpp"
#include "tristim/error.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/number.hpp"

namespace tristim {

namespace {

bool is_numeric_type(const std::string& type) {
  return type == "number" || type == "integer" || type == "boolean";
}

const OptionSpec* find_option(const MethodInfo& info, const std::string& name) {
  for (const auto& o : info.options)
    if (o.name == name) return &o;
  return nullptr;
}

std::string option_names(const MethodInfo& info) {
  std::string s;
  for (const auto& o : info.options) s += (s.empty() ? "" : ", ") + o.name;
  return s.empty() ? "none" : s;
}

}  // namespace

OptionSpec number_option(const std::string& name, const std::string& label, double default_number, double min,
                         double max, const std::string& description, const std::string& type) {
  OptionSpec o;
  o.name = name;
  o.type = type;
  o.label = label;
  o.default_number = default_number;
  o.min = min;
  o.max = max;
  o.description = description;
  return o;
}

OptionSpec text_option(const std::string& name, const std::string& label, const std::string& description,
                       const std::string& default_text, const std::vector<std::string>& choices) {
  OptionSpec o;
  o.name = name;
  o.type = choices.empty() ? "text" : "choice";
  o.label = label;
  o.default_text = default_text;
  o.choices = choices;
  o.description = description;
  return o;
}

std::string ids_of(const std::vector<MethodInfo>& rows, const std::string& separator) {
  std::string s;
  for (const auto& r : rows) s += (s.empty() ? "" : separator) + r.id;
  return s;
}

bool has_id(const std::vector<MethodInfo>& rows, const std::string& id) {
  for (const auto& r : rows)
    if (r.id == id) return true;
  return false;
}

MethodChoice complete_choice(const MethodInfo& info, const MethodChoice& choice) {
  MethodChoice out;
  out.method = info.id;
  auto unknown = [&](const std::string& name) {
    return Error(ErrorCode::UnknownId, "method '" + info.id + "' has no option '" + name +
                                           "' (options: " + option_names(info) + ")");
  };
  for (const auto& [name, value] : choice.parameters) {
    const OptionSpec* o = find_option(info, name);
    if (!o) throw unknown(name);
    if (!is_numeric_type(o->type))
      throw Error(ErrorCode::InvalidArgument, info.id + ": option '" + name + "' takes a text value");
    if (!std::isfinite(value))
      throw Error(ErrorCode::InvalidArgument, info.id + ": option '" + name + "' must be finite");
    if (o->type == "integer" && value != std::floor(value))
      throw Error(ErrorCode::InvalidArgument, info.id + ": option '" + name + "' must be an integer");
    if (o->type == "boolean" && value != 0 && value != 1)
      throw Error(ErrorCode::InvalidArgument, info.id + ": option '" + name + "' must be 0 or 1");
    if (o->min != o->max && (value < o->min || (o->min_exclusive && value == o->min) || value > o->max))
      throw Error(ErrorCode::InvalidArgument, info.id + ": option '" + name + "' = " + std::to_string(value) +
                                                  " is outside " + (o->min_exclusive ? "(" : "[") +
                                                  std::to_string(o->min) + ", " + std::to_string(o->max) + "]");
    out.parameters[name] = value;
  }
  for (const auto& [name, value] : choice.settings) {
    const OptionSpec* o = find_option(info, name);
    if (!o) throw unknown(name);
    if (is_numeric_type(o->type))
      throw Error(ErrorCode::InvalidArgument, info.id + ": option '" + name + "' takes a number");
    if (o->type == "choice") {
      bool ok = false;
      for (const auto& c : o->choices) ok = ok || c == value;
      if (!ok) throw Error(ErrorCode::InvalidArgument, info.id + ": '" + value + "' is not a value of option '" + name + "'");
    }
    out.settings[name] = value;
  }
  for (const auto& o : info.options) {
    if (is_numeric_type(o.type)) {
      if (!out.parameters.count(o.name)) out.parameters[o.name] = o.default_number;
    } else if (!out.settings.count(o.name)) {
      out.settings[o.name] = o.default_text;
    }
  }
  return out;
}

double choice_number(const MethodChoice& choice, const std::string& name) {
  const auto it = choice.parameters.find(name);
  if (it == choice.parameters.end())
    throw Error(ErrorCode::Internal, "method '" + choice.method + "': option '" + name + "' not set");
  return it->second;
}

const std::string& choice_text(const MethodChoice& choice, const std::string& name) {
  const auto it = choice.settings.find(name);
  if (it == choice.settings.end())
    throw Error(ErrorCode::Internal, "method '" + choice.method + "': option '" + name + "' not set");
  return it->second;
}

MethodChoice parse_choice(const std::string& text) {
  MethodChoice c;
  const auto colon = text.find(':');
  c.method = text.substr(0, colon);
  if (c.method.empty()) throw Error(ErrorCode::InvalidArgument, "'" + text + "': a method id is missing");
  if (colon == std::string::npos) return c;
  const std::string rest = text.substr(colon + 1);
  size_t start = 0;
  while (start <= rest.size()) {
    size_t end = rest.find(',', start);
    if (end == std::string::npos) end = rest.size();
    const std::string item = rest.substr(start, end - start);
    // A value may itself hold commas only as a ';'-separated list (e.g. grey=A1;A2;A3).
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error(ErrorCode::InvalidArgument, "'" + item + "' in '" + text + "' is not name=value");
    const std::string name = item.substr(0, eq), value = item.substr(eq + 1);
    char* stop = nullptr;
    const double d = tristim::parse_double(value.c_str(), &stop);
    if (!value.empty() && stop && *stop == '\0') c.parameters[name] = d;
    else c.settings[name] = value;
    start = end + 1;
  }
  return c;
}

}  // namespace tristim

namespace tristim::fields {

TRISTIM_FIELDS_DEFINE(OptionSpec, member<&OptionSpec::name>("name"), member<&OptionSpec::type>("type"),
                      member<&OptionSpec::label>("label"), member<&OptionSpec::default_number>("default_number"),
                      member<&OptionSpec::default_text>("default_text"), member<&OptionSpec::min>("min"),
                      member<&OptionSpec::max>("max"), member<&OptionSpec::choices>("choices"),
                      member<&OptionSpec::description>("description"), member<&OptionSpec::step>("step"),
                      member<&OptionSpec::unit>("unit"), member<&OptionSpec::min_exclusive>("min_exclusive"))
TRISTIM_FIELDS_DEFINE(MethodInfo, member<&MethodInfo::id>("id"), member<&MethodInfo::label>("label"),
                      member<&MethodInfo::reference>("reference"), member<&MethodInfo::options>("options"))
using LL = LinearisationListing;
TRISTIM_FIELDS_DEFINE(LinearisationListing, member<&LL::id>("id"), member<&LL::label>("label"),
                      member<&LL::reference>("reference"), member<&LL::needs>("needs"),
                      member<&LL::needs_text>("needs_text"), member<&LL::options>("options"))
TRISTIM_FIELDS_DEFINE(Monomial, member<&Monomial::r>("r"), member<&Monomial::g>("g"), member<&Monomial::b>("b"))
TRISTIM_FIELDS_DEFINE(ModelInfo, member<&ModelInfo::id>("id"), member<&ModelInfo::label>("label"),
                      member<&ModelInfo::reference>("reference"), member<&ModelInfo::n_terms>("n_terms"),
                      member<&ModelInfo::term_names>("term_names"), member<&ModelInfo::terms>("terms"),
                      member<&ModelInfo::root>("root"), member<&ModelInfo::linear>("linear"),
                      member<&ModelInfo::exposure_invariant>("exposure_invariant"),
                      member<&ModelInfo::duplicate_of>("duplicate_of"), member<&ModelInfo::family>("family"))
TRISTIM_FIELDS_DEFINE(ModelFamily, member<&ModelFamily::id>("id"), member<&ModelFamily::label>("label"),
                      member<&ModelFamily::about>("about"))

}  // namespace tristim::fields

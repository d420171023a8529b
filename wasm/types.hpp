// Conversions of core types that cross in a form of their own (shared by every bind_*.cpp, so each
// type converts the same way everywhere): enums as their ids, a MethodChoice also from the CLI's
// "id:name=value" text, a Recipe or a Profile also from its JSON text.
#pragma once
#include "boundary.hpp"
#include "tristim/absolute/fields.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/colorimetry/spectra.hpp"
#include "tristim/methods.hpp"
#include "tristim/profile/fields.hpp"
#include "tristim/profile/profile.hpp"
#include "tristim/profile/recipe.hpp"

namespace tristim::wasm {

inline Observer observer_of(const std::string& id) { return parse_observer(id); }
template <>
struct Conv<Observer> : EnumConv<Observer, &observer_name, &observer_of> {
  static Observer from(const val& v) {  // 1931 as a number works too
    return v.isNumber() ? parse_observer(std::to_string(v.as<int>())) : EnumConv::from(v);
  }
};
template <> struct Conv<Objective> : EnumConv<Objective, &objective_id, &objective_from_id> {};
inline FitStatus fit_status_of(const std::string& id) {
  for (FitStatus s : {FitStatus::Ok, FitStatus::IllConditioned, FitStatus::ExactlyDetermined, FitStatus::IterationLimit})
    if (id == fit_status_name(s)) return s;
  throw Error(ErrorCode::UnknownId, "unknown fit status '" + id + "'");
}
template <> struct Conv<FitStatus> : EnumConv<FitStatus, &fit_status_name, &fit_status_of> {};

template <>
struct Conv<MethodChoice> : SchemaConv<MethodChoice> {  // "psm:expansion=3" or {method, parameters, settings}
  static MethodChoice from(const val& v) { return v.isString() ? parse_choice(v.as<std::string>()) : SchemaConv<MethodChoice>::from(v); }
};
/// Metrics: its list's summaries and `patches`, the object PatchErrors' list writes — the CLI's
/// per-patch form (metrics_json) without the ids. A figure that is not a number is null.
template <>
struct Conv<Metrics> {
  static val to(const Metrics& m) { return to_js(metrics_json(m, {}, true)); }
  static Metrics from(const val& v) {
    Metrics m;
    if (absent(v)) return m;
    const json::Value o = from_js(v, "");
    fields::read_members(o, m, SchemaConv<Metrics>::context(), "", {"patches"});
    if (const json::Value* p = o.find("patches")) fields::read(*p, m.patches, SchemaConv<PatchErrors>::context(), "patches");
    return m;
  }
};
// The absolute mode's structs cross by their field lists (tristim/absolute/fields.hpp): an
// exposure is [t, N, ISO], a region row's rectangle is region: [x, y, w, h].
template <> struct Conv<ExposureSettings> : SchemaConv<ExposureSettings> {};
template <> struct ReadCode<AbsoluteRecipe> { static constexpr ErrorCode code = ErrorCode::RecipeInvalid; };
template <>
struct Conv<AbsoluteRecipe> : SchemaConv<AbsoluteRecipe> {  // the recipe JSON text, or its object
  static AbsoluteRecipe from(const val& v) {
    return v.isString() ? absolute_recipe_from_json(v.as<std::string>()) : SchemaConv<AbsoluteRecipe>::from(v);
  }
};
/// The report as its document (format, reference, then the listed members): what the CLI prints.
template <> struct Conv<AbsoluteReport> : JsonOutput<AbsoluteReport, &absolute_report_json> {};
template <>
struct Conv<Recipe> : SchemaConv<Recipe> {  // the recipe JSON text, or its object
  static Recipe from(const val& v) { return v.isString() ? recipe_from_json(v.as<std::string>()) : SchemaConv<Recipe>::from(v); }
};
/// A profile crosses as its document (format, version, then Profile's field list: what `tristim fit`
/// writes), and comes back from its JSON text or that object, read by the same reader.
template <>
struct Conv<Profile> {
  static val to(const Profile& p) { return to_js(profile_json(p)); }
  static Profile from(const val& v) {
    return v.isString() ? profile_from_json(v.as<std::string>()) : profile_from_document(from_js(v, "profile"));
  }
};

}  // namespace tristim::wasm

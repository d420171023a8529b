// Conversions of structs declared by a field list (io/fields.hpp; convert.hpp's rules): the object
// their JSON is, to JS and back through the list's strict reader. One list per struct gives the
// JSON, the CLI's output and these conversions (docs/architecture.md, "One field list per struct").
#pragma once
#include <cmath>
#include <string>

#include "convert.hpp"
#include "tristim/io/fields.hpp"

namespace tristim::wasm {

/// A JSON value as the JS value JSON.parse of its text gives (a number that is not finite: null).
inline val to_js(const json::Value& v) {
  switch (v.type()) {
    case json::Value::Type::Bool: return val(v.as_bool());
    case json::Value::Type::Number: return std::isfinite(v.as_number()) ? val(v.as_number()) : val::null();
    case json::Value::Type::String: return val(v.as_string());
    case json::Value::Type::Array: {
      val out = val::array();
      for (const auto& x : v.as_array()) out.call<void>("push", to_js(x));
      return out;
    }
    case json::Value::Type::Object: {
      val out = val::object();
      for (const auto& [k, x] : v.members()) out.set(k, to_js(x));
      return out;
    }
    default: return val::null();
  }
}
/// A JS value as JSON: typed arrays as arrays of numbers, NaN as null, undefined members left out.
inline json::Value from_js(const val& v, const std::string& path) {
  if (absent(v)) return {};
  if (v.isNumber()) {
    const double d = v.as<double>();
    return std::isfinite(d) ? json::Value(d) : json::Value();
  }
  if (v.isTrue() || v.isFalse()) return json::Value(v.as<bool>());
  if (v.isString()) return json::Value(v.as<std::string>());
  if (type_of(v) != "object") refuse("'" + path + "': expected JSON data, got " + type_of(v));
  if (val::global("ArrayBuffer").call<bool>("isView", v)) return json::Value(vector_from<double>(v));
  if (v.isArray()) {
    json::Value a = json::Value::array();
    for (size_t i = 0, n = v["length"].as<size_t>(); i < n; ++i) a.push(from_js(v[i], path + "[" + std::to_string(i) + "]"));
    return a;
  }
  json::Value o = json::Value::object();
  const val keys = val::global("Object").call<val>("keys", v);
  for (size_t i = 0, n = keys["length"].as<size_t>(); i < n; ++i) {
    const std::string k = keys[i].as<std::string>();
    if (!v[k].isUndefined()) o.set(k, from_js(v[k], fields::join(path, k)));
  }
  return o;
}
/// The error code of a refused object of T (ReadCode<AbsoluteRecipe>: RECIPE_INVALID).
template <class T> struct ReadCode { static constexpr ErrorCode code = ErrorCode::InvalidArgument; };
template <class T, class = void> struct SchemaName { static inline const std::string prefix; };
template <class T> struct SchemaName<T, std::void_t<decltype(fields::Schema<T>::name)>> {
  static inline const std::string prefix = std::string(fields::Schema<T>::name) + ": ";
};
/// A struct with a field list (io/fields.hpp) crosses as the object its JSON is — the names and
/// forms the CLI prints, written by the list — and comes back through the list's strict reader:
/// an unknown member refused (ReadCode<T>), a member left out keeps its C++ default, null reads
/// as NaN. The members are listed once, in C++, for JSON, the CLI and JS alike.
template <class T>
struct SchemaConv {
  static val to(const T& x) { return to_js(fields::write(x)); }
  static T from(const val& v) {
    T out{};
    if (!absent(v)) fields::read(from_js(v, ""), out, context());
    return out;
  }
  /// How a JS object of T is read (the code and prefix of a refusal, null as NaN, defaults kept).
  static fields::Context context() { return {ReadCode<T>::code, SchemaName<T>::prefix.c_str(), true, true}; }
};
template <class T>
struct Conv<T, std::enable_if_t<fields::has_schema<T>::value>> : SchemaConv<T> {};

}  // namespace tristim::wasm

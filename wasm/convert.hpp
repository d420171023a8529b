// Conversions between JS values and core types (Conv<T>::to / ::from), used by boundary.hpp's
// def<> and FIELD (the rules are in its header comment). Nothing here knows any colour science.
#pragma once
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"

namespace tristim::wasm {

using emscripten::val;

[[noreturn]] inline void refuse(const std::string& message) { throw Error(ErrorCode::InvalidArgument, message); }
inline bool absent(const val& v) { return v.isUndefined() || v.isNull(); }
inline std::string type_of(const val& v) { return v.typeOf().as<std::string>(); }

template <class T> struct TypedArray;
template <> struct TypedArray<double> { static constexpr const char* name = "Float64Array"; };
template <> struct TypedArray<float> { static constexpr const char* name = "Float32Array"; };
template <> struct TypedArray<int> { static constexpr const char* name = "Int32Array"; };
template <> struct TypedArray<uint8_t> { static constexpr const char* name = "Uint8Array"; };

/// A copy of n values as a new JS typed array (safe to keep across later calls).
template <class T>
val typed_array(const T* data, size_t n) {
  return val::global(TypedArray<T>::name).new_(emscripten::typed_memory_view(n, data));
}
/// A JS array-like of numbers (typed array or Array) -> std::vector, one copy.
template <class T>
std::vector<T> vector_from(const val& a) {
  if (absent(a)) return {};
  if (type_of(a) != "object" || a["length"].isUndefined()) refuse("expected an array of numbers, got " + type_of(a));
  const size_t n = a["length"].as<size_t>();
  std::vector<T> out(n);
  val view(emscripten::typed_memory_view(n, out.data()));
  if (a.instanceof(val::global(TypedArray<T>::name))) view.call<void>("set", a);
  else view.call<void>("set", val::global(TypedArray<T>::name).template call<val>("from", a));
  return out;
}

/// Conv<T>::to(const T&) -> val and Conv<T>::from(const val&) -> T (or what converts to T).
/// The primary template is for structs declared with value_object.
template <class T, class = void>
struct Conv {
  static val to(const T& x) { return val(x); }
  static T from(const val& v) {
    val full = val(T{});  // the C++ defaults, as a JS object with every declared field
    if (!absent(v)) {
      if (type_of(v) != "object" || v.isArray()) refuse("expected an object, got " + type_of(v));
      const val keys = val::global("Object").call<val>("keys", v);
      for (size_t i = 0, n = keys["length"].as<size_t>(); i < n; ++i) {
        const std::string k = keys[i].as<std::string>();
        if (!full.hasOwnProperty(k.c_str())) refuse("unknown field '" + k + "'");
        if (!v[k].isUndefined()) full.set(k, v[k]);
      }
    }
    return full.as<T>();
  }
};
template <class T>
struct Conv<T, std::enable_if_t<std::is_arithmetic_v<T>>> {
  static val to(T x) {
    if constexpr (sizeof(T) > 4) return val(static_cast<double>(x));  // no BigInt: 64-bit ints as doubles
    else return val(x);
  }
  static T from(const val& v) {
    if (absent(v)) return T{};
    if (!v.isNumber() && !v.isTrue() && !v.isFalse()) refuse("expected a number, got " + type_of(v));
    return static_cast<T>(v.as<double>());
  }
};
template <>
struct Conv<std::string> {
  static val to(const std::string& s) { return val(s); }
  static std::string from(const val& v) {
    if (absent(v)) return {};
    if (!v.isString()) refuse("expected a string, got " + type_of(v));
    return v.as<std::string>();
  }
};
template <>
struct Conv<std::string_view> {
  static val to(std::string_view s) { return val(std::string(s)); }
  static std::string from(const val& v) { return Conv<std::string>::from(v); }
};
template <class T>
struct Conv<std::vector<T>> {
  static val to(const std::vector<T>& v) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      return typed_array(v.data(), v.size());
    } else {
      val out = val::array();
      for (const auto& x : v) out.call<void>("push", Conv<T>::to(x));
      return out;
    }
  }
  static std::vector<T> from(const val& a) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
      return vector_from<T>(a);
    } else {
      std::vector<T> out;
      if (absent(a)) return out;
      if (!a.isArray()) refuse("expected an array, got " + type_of(a));
      for (size_t i = 0, n = a["length"].as<size_t>(); i < n; ++i) out.push_back(Conv<T>::from(a[i]));
      return out;
    }
  }
};
template <class V>
struct Conv<std::map<std::string, V>> {
  static val to(const std::map<std::string, V>& m) {
    val out = val::object();
    for (const auto& [k, x] : m) out.set(k, Conv<V>::to(x));
    return out;
  }
  static std::map<std::string, V> from(const val& v) {
    std::map<std::string, V> out;
    if (absent(v)) return out;
    if (type_of(v) != "object" || v.isArray()) refuse("expected an object, got " + type_of(v));
    const val keys = val::global("Object").call<val>("keys", v);
    for (size_t i = 0, n = keys["length"].as<size_t>(); i < n; ++i) {
      const std::string k = keys[i].as<std::string>();
      out[k] = Conv<V>::from(v[k]);
    }
    return out;
  }
};
/// The value_object conversion, for a specialisation that accepts another form as well.
template <class T> using StructConv = Conv<T, int>;

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
template <class T, class = void> struct SchemaName { static constexpr const char* prefix = ""; };
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
    if (absent(v)) return out;
    fields::Context c{ReadCode<T>::code, ""};
    const std::string prefix = SchemaName<T>::prefix;
    c.prefix = prefix.c_str();
    c.null_is_nan = true;
    c.missing_is_default = true;
    fields::read(from_js(v, ""), out, c);
    return out;
  }
};
template <class T>
struct Conv<T, std::enable_if_t<fields::has_schema<T>::value>> : SchemaConv<T> {};
/// Enums cross as their ids: Conv<E> from a pair of functions (id of a value, value of an id).
template <class E, const char* (*Name)(E), E (*Parse)(const std::string&)>
struct EnumConv {
  static val to(E e) { return val(std::string(Name(e))); }
  static E from(const val& v) { return absent(v) ? E{} : Parse(Conv<std::string>::from(v)); }
};

}  // namespace tristim::wasm

#include "convert_numeric.hpp"  // fixed-size arrays, Vec3, matrices

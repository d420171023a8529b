// Conversions between JS values and core types (Conv<T>::to / ::from), used by boundary.hpp's
// def<> and FIELD (the rules are in its header comment). Nothing here knows any colour science.
#pragma once
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"

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
/// The primary template is for structs declared with value_object (structs with a field list:
/// convert_fields.hpp).
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

/// Enums cross as their ids: Conv<E> from a pair of functions (id of a value, value of an id).
template <class E, const char* (*Name)(E), E (*Parse)(const std::string&)>
struct EnumConv {
  static val to(E e) { return val(std::string(Name(e))); }
  static E from(const val& v) { return absent(v) ? E{} : Parse(Conv<std::string>::from(v)); }
};

}  // namespace tristim::wasm

#include "convert_numeric.hpp"  // fixed-size arrays, Vec3, matrices
#include "convert_fields.hpp"   // structs with a field list

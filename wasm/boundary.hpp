// The boundary between embind and the core: errors, value conversions and the two declaration
// helpers every bind_*.cpp uses. Nothing here knows any colour science. Bind files include
// types.hpp (which includes this), so every type converts the same way in every file.
//
//   def<&core_function>("jsName")   binds a core function as it is: its arguments and result are
//                                   converted by Conv<T>, any exception becomes a JS Error with
//                                   `.code`, and trailing arguments may be omitted (they take
//                                   their type's default: 0, "", [], or a struct's C++ defaults).
//   FIELD(name)                     one field of a value_object, converted by Conv<T>.
//
// Conversions (JS <-> C++): numbers, booleans, strings; std::vector<number> <-> typed array
// (Float64Array, Float32Array, Int32Array, Uint8Array); other vectors <-> Array; std::array and
// Vec3 <-> Array; std::vector<Vec3> and PatchMatrix <-> Float64Array(3N), patch-major; Mat3 and
// Eigen::MatrixXd (3 × P coefficients) <-> row-major Float64Array; std::map<string, V> <-> object;
// declared structs (value_object) <-> plain objects with the C++ field names, where a field left
// out takes the struct's C++ default and an unknown field is refused (INVALID_ARGUMENT).
#pragma once
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <array>
#include <map>
#include <new>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"

namespace tristim::wasm {

using emscripten::val;

/// Runs f(); turns any C++ exception into a thrown JS Error with `.code` (the ErrorCode name). The
/// JS error is thrown after the C++ exception is fully handled.
template <class F>
auto guard(F&& f) -> decltype(f()) {
  std::string code = "INTERNAL", message;
  try {
    return f();
  } catch (const Error& e) {
    code = e.code_name();
    message = e.what();
  } catch (const std::bad_alloc&) {
    code = "OUT_OF_MEMORY";
    message = "out of memory (the image may be too large for the browser)";
  } catch (const std::exception& e) {
    message = std::string("internal error: ") + e.what();
  } catch (...) {
    message = "internal error (unknown exception)";
  }
  val err = val::global("Error").new_(val(message));
  err.set("code", val(code));
  err.throw_();
}

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
/// Fixed-size numbers: a plain Array (corners, triplets, 3 × 3 matrices).
template <class T, size_t N>
struct Conv<std::array<T, N>> {
  static val to(const std::array<T, N>& a) {
    val out = val::array();
    for (const auto& x : a) out.call<void>("push", Conv<T>::to(x));
    return out;
  }
  static std::array<T, N> from(const val& v) {
    std::array<T, N> out{};
    if (absent(v)) return out;
    if constexpr (std::is_arithmetic_v<T>) {
      const auto d = vector_from<double>(v);
      if (d.size() != N) refuse("expected " + std::to_string(N) + " numbers, got " + std::to_string(d.size()));
      for (size_t i = 0; i < N; ++i) out[i] = static_cast<T>(d[i]);
    } else {  // an Array of N elements, each converted as a T (per-channel curves, ranges)
      if (type_of(v) != "object" || v["length"].isUndefined() || v["length"].as<size_t>() != N)
        refuse("expected an array of " + std::to_string(N) + " elements");
      for (size_t i = 0; i < N; ++i) out[i] = Conv<T>::from(v[i]);
    }
    return out;
  }
};
template <>
struct Conv<Vec3> {
  static val to(const Vec3& v) { return Conv<std::array<double, 3>>::to({v[0], v[1], v[2]}); }
  static Vec3 from(const val& v) {
    if (absent(v)) refuse("expected [X, Y, Z]");
    const auto a = Conv<std::array<double, 3>>::from(v);
    return Vec3(a[0], a[1], a[2]);
  }
};
/// Row-major matrices: Mat3 (9 values) and the 3 × P coefficients of a model (3P values).
template <class M>
struct MatrixConv {
  static val to(const M& m) {
    std::vector<double> v(m.size());
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) v[r * m.cols() + c] = m(r, c);
    return typed_array(v.data(), v.size());
  }
  static M from(const val& a) {
    const auto v = vector_from<double>(a);
    if (v.size() % 3 != 0) refuse("length " + std::to_string(v.size()) + " is not a multiple of 3");
    const Eigen::Index n = static_cast<Eigen::Index>(v.size() / 3);
    constexpr bool patches = M::RowsAtCompileTime == Eigen::Dynamic && M::ColsAtCompileTime == 3;  // N × 3
    M m(patches ? n : 3, M::ColsAtCompileTime == Eigen::Dynamic ? n : 3);
    if (static_cast<size_t>(m.size()) != v.size()) refuse("expected " + std::to_string(m.size()) + " values");
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) m(r, c) = v[r * m.cols() + c];
    return m;
  }
};
template <> struct Conv<Mat3> : MatrixConv<Mat3> {};
template <> struct Conv<Eigen::MatrixXd> : MatrixConv<Eigen::MatrixXd> {};
template <> struct Conv<Eigen::Matrix<double, Eigen::Dynamic, 3>> : MatrixConv<Eigen::Matrix<double, Eigen::Dynamic, 3>> {};
template <>
struct Conv<std::vector<Vec3>> {
  static val to(const std::vector<Vec3>& v) {
    std::vector<double> flat;
    flat.reserve(3 * v.size());
    for (const auto& x : v) flat.insert(flat.end(), {x[0], x[1], x[2]});
    return typed_array(flat.data(), flat.size());
  }
  static std::vector<Vec3> from(const val& a) {
    const auto d = vector_from<double>(a);
    if (d.size() % 3 != 0) refuse("length " + std::to_string(d.size()) + " is not a multiple of 3");
    std::vector<Vec3> out;
    for (size_t i = 0; i < d.size(); i += 3) out.emplace_back(d[i], d[i + 1], d[i + 2]);
    return out;
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

// ---- declarations -------------------------------------------------------------------------

template <class T> struct member_of;
template <class C, class F> struct member_of<F C::*> { using cls = C; using type = F; };
template <auto M>
val get_field(const typename member_of<decltype(M)>::cls& o) { return Conv<typename member_of<decltype(M)>::type>::to(o.*M); }
template <auto M>
void set_field(typename member_of<decltype(M)>::cls& o, val v) { o.*M = Conv<typename member_of<decltype(M)>::type>::from(v); }
/// In `value_object<S>(...)`: FIELD(name) declares S::name under the same name.
#define FIELD(name) .field(#name, &::tristim::wasm::get_field<&S::name>, &::tristim::wasm::set_field<&S::name>)

template <class T> using Stored = std::decay_t<T>;
template <class T, size_t> struct Always { using type = T; };

template <auto F> struct Fn;
template <class R, class... A, R (*F)(A...)>
struct Fn<F> {
  static constexpr size_t arity = sizeof...(A);
  template <size_t... I>
  static val invoke(const std::vector<val>& a, std::index_sequence<I...>) {
    return guard([&] {
      if constexpr (std::is_void_v<R>) {
        F(Conv<Stored<A>>::from(a[I])...);
        return val::undefined();
      } else {
        return Conv<Stored<R>>::to(F(Conv<Stored<A>>::from(a[I])...));
      }
    });
  }
  /// The JS entry point taking the first K arguments; the others are undefined.
  template <class Seq> struct First;
  template <size_t... K>
  struct First<std::index_sequence<K...>> {
    static val call(typename Always<val, K>::type... given) {
      std::vector<val> a(arity, val::undefined());
      ((a[K] = given), ...);
      return invoke(a, std::make_index_sequence<arity>{});
    }
  };
  template <size_t... K>
  static void declare(const char* name, std::index_sequence<K...>) {
    (emscripten::function(name, &First<std::make_index_sequence<K>>::call), ...);
  }
};

/// Binds core function F as `name` (see the header comment).
template <auto F>
void def(const char* name) { Fn<F>::declare(name, std::make_index_sequence<Fn<F>::arity + 1>{}); }

}  // namespace tristim::wasm

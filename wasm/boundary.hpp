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
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "convert.hpp"
#include "tristim/io/json.hpp"

namespace tristim::wasm {

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

/// A core output with a JSON writer made from its field list (io/fields.hpp) crosses as the object
/// its JSON is: the members, names and numbers the CLI prints (non-finite numbers: null). Use as
/// `template <> struct Conv<T> : JsonOutput<T, &t_json> {};`.
template <class T, json::Value (*Write)(const T&)>
struct JsonOutput {
  static val to(const T& t) { return val::global("JSON").call<val>("parse", val(Write(t).dump())); }
  static T from(const val&) { refuse("an output of the engine, not an input"); }
};

/// Binds core function F as `name` (see the header comment).
template <auto F>
void def(const char* name) { Fn<F>::declare(name, std::make_index_sequence<Fn<F>::arity + 1>{}); }

}  // namespace tristim::wasm

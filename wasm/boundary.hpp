// Boundary conversions between embind and the core. Nothing here knows any colour science.
#pragma once
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include "tristim/error.hpp"

namespace tristim::wasm {

using emscripten::val;

/// A JS Error with `.code` (the ErrorCode name) and the core's message.
inline val make_js_error(const char* code, const std::string& message) {
  val err = val::global("Error").new_(val(message));
  err.set("code", val(code));
  return err;
}

/// Runs f(); turns any C++ exception into a thrown JS Error with a code. The JS error is thrown
/// after the C++ exception is fully handled, so no C++ object is left half-destroyed.
template <class F>
auto guard(F&& f) -> decltype(f()) {
  val err = val::undefined();
  try {
    return f();
  } catch (const Error& e) {
    err = make_js_error(e.code_name(), e.what());
  } catch (const std::bad_alloc&) {
    err = make_js_error("OUT_OF_MEMORY", "out of memory (the image may be too large for the browser)");
  } catch (const std::exception& e) {
    err = make_js_error("INTERNAL", std::string("internal error: ") + e.what());
  } catch (...) {
    err = make_js_error("INTERNAL", "internal error (unknown exception)");
  }
  err.throw_();
}

/// JS Uint8Array -> bytes, one copy.
inline std::vector<uint8_t> bytes_from_js(const val& array) {
  const size_t n = array["length"].as<size_t>();
  std::vector<uint8_t> out(n);
  val view(emscripten::typed_memory_view(n, out.data()));
  view.call<void>("set", array);
  return out;
}

/// A copy of doubles as a new JS Float64Array (safe to keep across later calls).
inline val float64_array(const double* data, size_t n) {
  return val::global("Float64Array").new_(emscripten::typed_memory_view(n, data));
}
inline val float32_array(const float* data, size_t n) {
  return val::global("Float32Array").new_(emscripten::typed_memory_view(n, data));
}

/// JS array-like of numbers -> std::vector<double>.
inline std::vector<double> doubles_from_js(const val& array) {
  return emscripten::convertJSArrayToNumberVector<double>(array);
}

}  // namespace tristim::wasm

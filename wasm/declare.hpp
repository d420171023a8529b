// STRUCT(T, a, b, …): the value_object of a struct whose JS name and field names are its C++ names,
// each said once — value_object<T>("T") FIELD(a) FIELD(b) …. A struct with a field of its own
// conversion (.field("W", get, set)) keeps the long form.
#pragma once
#include "boundary.hpp"

// FOR_EACH over up to 256 arguments: each pass of an expansion level rescans the next step.
#define TRISTIM_PARENS ()
#define TRISTIM_EXPAND(...) TRISTIM_EXPAND3(TRISTIM_EXPAND3(TRISTIM_EXPAND3(TRISTIM_EXPAND3(__VA_ARGS__))))
#define TRISTIM_EXPAND3(...) TRISTIM_EXPAND2(TRISTIM_EXPAND2(TRISTIM_EXPAND2(TRISTIM_EXPAND2(__VA_ARGS__))))
#define TRISTIM_EXPAND2(...) TRISTIM_EXPAND1(TRISTIM_EXPAND1(TRISTIM_EXPAND1(TRISTIM_EXPAND1(__VA_ARGS__))))
#define TRISTIM_EXPAND1(...) __VA_ARGS__
#define TRISTIM_FOR_EACH(m, ...) __VA_OPT__(TRISTIM_EXPAND(TRISTIM_FOR_EACH_STEP(m, __VA_ARGS__)))
#define TRISTIM_FOR_EACH_STEP(m, a, ...) m(a) __VA_OPT__(TRISTIM_FOR_EACH_AGAIN TRISTIM_PARENS(m, __VA_ARGS__))
#define TRISTIM_FOR_EACH_AGAIN() TRISTIM_FOR_EACH_STEP

#define STRUCT(T, ...)                                                   \
  {                                                                      \
    using S = T;                                                         \
    ::emscripten::value_object<S>(#T) TRISTIM_FOR_EACH(FIELD, __VA_ARGS__); \
  }

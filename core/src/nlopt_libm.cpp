// The C functions core/src/nlopt_libm.h routes NLopt's sin, cos and atan to (compiled into the
// nlopt target, cmake/nlopt.cmake): detmath's, the same bits in every build.
#include "detmath.hpp"

extern "C" {
double tristim_nlopt_sin(double x) { return tristim::detmath::sin(x); }
double tristim_nlopt_cos(double x) { return tristim::detmath::cos(x); }
double tristim_nlopt_atan(double x) { return tristim::detmath::atan2(x, 1.0); }
}

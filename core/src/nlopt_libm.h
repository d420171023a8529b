/* Forced into every C file of NLopt (cmake/nlopt.cmake): sin, cos and atan are tristim's detmath
   (core/src/detmath.hpp), which gives the same bits natively (glibc) and in wasm (musl), so that
   NEWUOA takes the same steps in both builds. C, as NLopt is. */
#ifndef TRISTIM_NLOPT_LIBM_H
#define TRISTIM_NLOPT_LIBM_H
#include <math.h>
double tristim_nlopt_sin(double x);
double tristim_nlopt_cos(double x);
double tristim_nlopt_atan(double x);
#define sin(x) tristim_nlopt_sin(x)
#define cos(x) tristim_nlopt_cos(x)
#define atan(x) tristim_nlopt_atan(x)
#endif

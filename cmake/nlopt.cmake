# NLopt 2.7 for every build (native, wasm, fuzz), compiled from Debian's source package that
# scripts/install-deps.sh unpacked into TRISTIM_THIRD_PARTY_DIR: its own CMake build, static, C API
# only. Nothing here is committed third-party source: only how to compile it.
#
# Natively and in wasm the same code must take the same steps, so that a fit in the page gives the
# numbers of the command line to the bit (tests/core/characterisation/models_test.cpp, "NLopt's
# other optimisers …", pins them in both builds). Debian's libnlopt.so did not: its
# code is the same but it calls the C library, which differs between glibc (native) and musl
# (Emscripten):
#  - SBPLX sorts its subspaces with nlopt_qsort_r, which is glibc's qsort_r natively (a merge sort)
#    and NLopt's own quicksort in wasm: ties came out in another order (3x3, 24 patches: 1800
#    evaluations natively, 1195 in wasm). HAVE_QSORT_R is set false, so both use NLopt's own sort.
#  - NEWUOA turns its trust-region steps with sin, cos and atan, which glibc and musl round
#    differently in the last place (root-polynomial 2: 884 evaluations natively, 605 in wasm).
#    Every C file of NLopt is compiled with core/src/nlopt_libm.h forced in, which routes those
#    three to tristim's detmath (core/src/detmath.hpp: the same bits in every build).
# (PRAXIS draws random numbers: fit.cpp seeds NLopt's generator before every run.)
include(${CMAKE_SOURCE_DIR}/cmake/source_packages.cmake)  # tristim_find_src
tristim_find_src(NLOPT_DIR "nlopt-2*" "NLopt")
set(BUILD_SHARED_LIBS OFF CACHE BOOL "" FORCE)
foreach(opt NLOPT_CXX NLOPT_FORTRAN NLOPT_PYTHON NLOPT_OCTAVE NLOPT_MATLAB NLOPT_GUILE NLOPT_SWIG NLOPT_TESTS)
  set(${opt} OFF CACHE BOOL "" FORCE)
endforeach()
if(EMSCRIPTEN)
  set(WITH_THREADLOCAL OFF CACHE BOOL "" FORCE)  # no threads in the module
endif()                                          # natively: the generator's state per thread
set(HAVE_QSORT_R "" CACHE INTERNAL "NLopt's own sort in every build (cmake/nlopt.cmake)")
add_subdirectory(${NLOPT_DIR} ${CMAKE_BINARY_DIR}/nlopt EXCLUDE_FROM_ALL)
set_target_properties(nlopt PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_compile_options(nlopt PRIVATE -w $<$<COMPILE_LANGUAGE:C>:-include ${CMAKE_SOURCE_DIR}/core/src/nlopt_libm.h>)
target_sources(nlopt PRIVATE ${CMAKE_SOURCE_DIR}/core/src/nlopt_libm.cpp)
target_include_directories(nlopt PRIVATE ${CMAKE_SOURCE_DIR}/core/src)
if(EMSCRIPTEN)
  # BOBYQA's subroutines kept as functions (see the top-level CMakeLists.txt: V8 runs the one merged
  # function ~2.6x slower than the same code natively, the separate functions ~1.3x).
  set_source_files_properties(${NLOPT_DIR}/src/algs/bobyqa/bobyqa.c TARGET_DIRECTORY nlopt
                              PROPERTIES COMPILE_OPTIONS -fno-inline)
endif()
add_library(tristim_nlopt INTERFACE)
target_link_libraries(tristim_nlopt INTERFACE nlopt)

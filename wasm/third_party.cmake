# Builds LibRaw, lcms2 and NLopt for WebAssembly from Debian's source packages that
# scripts/install-deps.sh unpacked into TRISTIM_THIRD_PARTY_DIR. Nothing here is committed
# third-party source: only the list of what to compile and how.

function(tristim_find_src out pattern what)
  file(GLOB dirs LIST_DIRECTORIES true "${TRISTIM_THIRD_PARTY_DIR}/${pattern}")
  set(found "")
  foreach(d ${dirs})
    if(IS_DIRECTORY ${d})
      set(found ${d})
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "${what} source not found in ${TRISTIM_THIRD_PARTY_DIR}: "
                        "run scripts/install-deps.sh (it fetches Debian's source package)")
  endif()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

# --- LibRaw 0.20: no CMake build. Sources = lib_libraw_a_SOURCES of Makefile.am (up to the next
# blank line); libraw_cxx.cpp and *_ph.cpp are include-only, hence no glob.
tristim_find_src(LIBRAW_DIR "libraw-0*" "LibRaw")
file(READ ${LIBRAW_DIR}/Makefile.am am)
string(REGEX MATCH "lib_libraw_a_SOURCES =[^\n]*(\n[^\n]+)*" block "${am}")
string(REGEX MATCHALL "src/[A-Za-z0-9_/]+\\.cpp" libraw_rel "${block}")
list(LENGTH libraw_rel n_libraw)
if(n_libraw LESS 60)
  message(FATAL_ERROR "could not read LibRaw's source list from ${LIBRAW_DIR}/Makefile.am")
endif()
set(libraw_src "")
foreach(s ${libraw_rel})
  list(APPEND libraw_src ${LIBRAW_DIR}/${s})
endforeach()
add_library(libraw_wasm STATIC ${libraw_src})
target_include_directories(libraw_wasm PUBLIC ${LIBRAW_DIR})
# LIBRAW_NOTHREADS: no pthreads in our wasm; -w: LibRaw's own warnings are not ours to fix.
target_compile_definitions(libraw_wasm PUBLIC LIBRAW_NOTHREADS)
target_compile_options(libraw_wasm PRIVATE -w -O3 -fexceptions)
add_library(tristim_libraw INTERFACE)
target_link_libraries(tristim_libraw INTERFACE libraw_wasm)

# --- lcms2: every C file of src/.
tristim_find_src(LCMS2_DIR "lcms2-2*" "lcms2")
file(GLOB lcms2_src ${LCMS2_DIR}/src/*.c)
add_library(lcms2_wasm STATIC ${lcms2_src})
target_include_directories(lcms2_wasm PUBLIC ${LCMS2_DIR}/include)
target_compile_options(lcms2_wasm PRIVATE -w -O3)
add_library(tristim_lcms2 INTERFACE)
target_link_libraries(tristim_lcms2 INTERFACE lcms2_wasm)

# --- NLopt: its own CMake build, static, C API only, no bindings or tests.
tristim_find_src(NLOPT_DIR "nlopt-2*" "NLopt")
set(BUILD_SHARED_LIBS OFF CACHE BOOL "" FORCE)
foreach(opt NLOPT_CXX NLOPT_FORTRAN NLOPT_PYTHON NLOPT_OCTAVE NLOPT_MATLAB NLOPT_GUILE NLOPT_SWIG NLOPT_TESTS)
  set(${opt} OFF CACHE BOOL "" FORCE)
endforeach()
set(WITH_THREADLOCAL OFF CACHE BOOL "" FORCE)
add_subdirectory(${NLOPT_DIR} ${CMAKE_BINARY_DIR}/nlopt EXCLUDE_FROM_ALL)
target_compile_options(nlopt PRIVATE -w)
add_library(tristim_nlopt INTERFACE)
target_link_libraries(tristim_nlopt INTERFACE nlopt)

# Shared by the wasm build (cmake/wasm_third_party.cmake) and the fuzz build (TRISTIM_FUZZ, top-level
# CMakeLists.txt): finding the Debian source packages that scripts/install-deps.sh unpacked into
# TRISTIM_THIRD_PARTY_DIR, and LibRaw's list of sources. Nothing here is committed third-party
# source: only the list of what to compile.

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

# The sources a package's own build file lists: in ${dir}/${file}, the block matching `block_regex`,
# the names in it matching `name_regex`, as paths under `dir`. Fewer than `min`: a fatal error
# naming the file (its format changed), rather than a library missing half its sources.
function(tristim_read_source_list out dir file block_regex name_regex min what)
  file(READ ${dir}/${file} text)
  string(REGEX MATCH "${block_regex}" block "${text}")
  string(REGEX MATCHALL "${name_regex}" rel "${block}")
  list(LENGTH rel n)
  if(n LESS ${min})
    message(FATAL_ERROR "could not read ${what}'s source list from ${dir}/${file}")
  endif()
  list(TRANSFORM rel PREPEND ${dir}/)
  set(${out} ${rel} PARENT_SCOPE)
endfunction()

# LibRaw 0.20 as a static library `target` (compiled with the caller's directory-wide options,
# e.g. the sanitizers of the fuzz build). LibRaw has no CMake build. Sources =
# lib_libraw_a_SOURCES of Makefile.am (up to the next blank line); libraw_cxx.cpp and *_ph.cpp
# are include-only, hence no glob. LIBRAW_NOTHREADS (wasm, which has no pthreads, and the fuzzers,
# which run one input at a time): single-threaded use only; the native build keeps LibRaw's
# thread-local state.
function(tristim_add_libraw_from_source target)
  tristim_find_src(LIBRAW_DIR "libraw-0*" "LibRaw")
  tristim_read_source_list(libraw_src ${LIBRAW_DIR} Makefile.am "lib_libraw_a_SOURCES =[^\n]*(\n[^\n]+)*"
                           "src/[A-Za-z0-9_/]+\\.cpp" 60 "LibRaw")
  add_library(${target} STATIC ${libraw_src})
  target_include_directories(${target} PUBLIC ${LIBRAW_DIR})
  if(EMSCRIPTEN OR TRISTIM_FUZZ)
    target_compile_definitions(${target} PUBLIC LIBRAW_NOTHREADS)
  endif()
  target_compile_options(${target} PRIVATE -w)  # LibRaw's own warnings are not ours to fix
endfunction()

# Native build only (included by tests/CMakeLists.txt): each libFuzzer target of tests/fuzz
# compiled with replay_main.cpp instead of libFuzzer, and a ctest `native:fuzz-replay:<target>`
# that runs it over tests/fuzz/corpus/<target> — the seeds and every crash ever found.
file(GLOB _fuzz_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/fuzz_*.cpp)
list(FILTER _fuzz_sources EXCLUDE REGEX "fuzz_image\\.cpp$")
set(_fuzz_replays "")
foreach(src ${_fuzz_sources})
  get_filename_component(name ${src} NAME_WE)
  string(REGEX REPLACE "^fuzz_" "" corpus ${name})
  add_executable(replay_${corpus} ${src} ${CMAKE_CURRENT_LIST_DIR}/replay_main.cpp)
  list(APPEND _fuzz_replays ${corpus})
endforeach()
set(_fuzz_id 1)
foreach(f tiff png jpeg)  # fuzz_image.cpp: 1 TIFF, 2 PNG, 3 JPEG (tests/fuzz/CMakeLists.txt)
  add_executable(replay_${f} ${CMAKE_CURRENT_LIST_DIR}/fuzz_image.cpp ${CMAKE_CURRENT_LIST_DIR}/replay_main.cpp)
  target_compile_definitions(replay_${f} PRIVATE TRISTIM_FUZZ_FORMAT=${_fuzz_id})
  list(APPEND _fuzz_replays ${f})
  math(EXPR _fuzz_id "${_fuzz_id} + 1")
endforeach()
foreach(corpus ${_fuzz_replays})
  target_link_libraries(replay_${corpus} PRIVATE tristim_core)
  add_test(NAME native:fuzz-replay:${corpus}
           COMMAND replay_${corpus} ${CMAKE_CURRENT_LIST_DIR}/corpus/${corpus})
endforeach()

# Builds LibRaw, lcms2 and NLopt for WebAssembly from Debian's source packages that
# scripts/install-deps.sh unpacked into TRISTIM_THIRD_PARTY_DIR. Nothing here is committed
# third-party source: only the list of what to compile and how.

include(${CMAKE_SOURCE_DIR}/cmake/source_packages.cmake)  # tristim_find_src, LibRaw's source list

# A static library of a package's C sources (its own warnings are not ours to fix), and, given
# INTERFACE_NAME, the tristim_* target the core links (natively that one wraps Debian's package).
function(tristim_wasm_library name)
  cmake_parse_arguments(A "" "INTERFACE_NAME" "SOURCES;INCLUDES;LINKS" ${ARGN})
  add_library(${name} STATIC ${A_SOURCES})
  target_include_directories(${name} PUBLIC ${A_INCLUDES})
  if(A_LINKS)
    target_link_libraries(${name} PUBLIC ${A_LINKS})
  endif()
  target_compile_options(${name} PRIVATE -w -O3)
  if(A_INTERFACE_NAME)
    add_library(${A_INTERFACE_NAME} INTERFACE)
    target_link_libraries(${A_INTERFACE_NAME} INTERFACE ${name})
  endif()
endfunction()

# --- LibRaw 0.20 (cmake/source_packages.cmake); exceptions on: LibRaw reports errors by throwing.
tristim_add_libraw_from_source(libraw_wasm)
target_compile_options(libraw_wasm PRIVATE -O3 ${TRISTIM_WASM_EXCEPTIONS})
add_library(tristim_libraw INTERFACE)
target_link_libraries(tristim_libraw INTERFACE libraw_wasm)

# --- lcms2: every C file of src/.
tristim_find_src(LCMS2_DIR "lcms2-2*" "lcms2")
file(GLOB lcms2_src ${LCMS2_DIR}/src/*.c)
tristim_wasm_library(lcms2_wasm INTERFACE_NAME tristim_lcms2 SOURCES ${lcms2_src} INCLUDES ${LCMS2_DIR}/include)

# --- NLopt: cmake/nlopt.cmake, as natively (the same steps in both builds).
include(${CMAKE_SOURCE_DIR}/cmake/nlopt.cmake)

# ---------------------------------------------------------------------------------------------
# Images in (core/src/capture/image_*.cpp): zlib, libpng, libjpeg-turbo and libtiff, each from its
# Debian source package (with Debian's patches, as apt-get source unpacks it), compiled once per
# build directory. Only the codecs the core reads are built: libtiff with none/LZW/PackBits/
# Deflate/JPEG (the core refuses every other compression natively too, so both builds agree).

# --- zlib: the library's C files (no gz* file I/O).
tristim_find_src(ZLIB_DIR "zlib-1*" "zlib")
set(zlib_src "")
foreach(f adler32 compress crc32 deflate infback inffast inflate inftrees trees uncompr zutil)
  list(APPEND zlib_src ${ZLIB_DIR}/${f}.c)
endforeach()
tristim_wasm_library(zlib_wasm SOURCES ${zlib_src} INCLUDES ${ZLIB_DIR})

# --- libpng 1.6: libpng_sources of its CMakeLists.txt (no hardware-specific files in wasm); the
# configuration header is the upstream default, scripts/pnglibconf.h.prebuilt.
tristim_find_src(PNG_DIR "libpng1.6-1*" "libpng")
tristim_read_source_list(png_src ${PNG_DIR} CMakeLists.txt "set\\(libpng_sources[^)]*\\)" "png[a-z]*\\.c" 15 "libpng")
configure_file(${PNG_DIR}/scripts/pnglibconf.h.prebuilt ${CMAKE_BINARY_DIR}/third_party/png/pnglibconf.h COPYONLY)
tristim_wasm_library(png_wasm INTERFACE_NAME tristim_png SOURCES ${png_src}
                     INCLUDES ${PNG_DIR} ${CMAKE_BINARY_DIR}/third_party/png LINKS zlib_wasm)

# --- libjpeg-turbo 2.1: JPEG_SOURCES of its CMakeLists.txt plus arithmetic coding and the
# no-SIMD stubs; the libjpeg 6b API, as Debian's libjpeg62-turbo. Configuration headers from its
# own templates.
tristim_find_src(JPEG_DIR "libjpeg-turbo-2*" "libjpeg-turbo")
function(tristim_configure_libjpeg dir out)
  file(READ ${dir}/CMakeLists.txt jpeg_cmake)
  string(REGEX MATCH "set\\(VERSION ([0-9]+)\\.([0-9]+)\\.([0-9]+)\\)" _ "${jpeg_cmake}")
  set(VERSION ${CMAKE_MATCH_1}.${CMAKE_MATCH_2}.${CMAKE_MATCH_3})
  math(EXPR LIBJPEG_TURBO_VERSION_NUMBER "${CMAKE_MATCH_1} * 1000000 + ${CMAKE_MATCH_2} * 1000 + ${CMAKE_MATCH_3}")
  set(JPEG_LIB_VERSION 62)
  set(C_ARITH_CODING_SUPPORTED 1)
  set(D_ARITH_CODING_SUPPORTED 1)
  set(MEM_SRCDST_SUPPORTED 1)
  set(WITH_SIMD 0)
  set(BITS_IN_JSAMPLE 8)
  set(BUILD "debian-wasm")
  set(INLINE "inline __attribute__((always_inline))")
  set(THREAD_LOCAL "")            # no threads in our wasm
  set(CMAKE_PROJECT_NAME "libjpeg-turbo")
  set(SIZE_T 4)                   # wasm32
  set(HAVE_BUILTIN_CTZL 1)
  set(COPYRIGHT_YEAR "1991-2023")
  configure_file(${dir}/jconfig.h.in ${out}/jconfig.h)
  configure_file(${dir}/jconfigint.h.in ${out}/jconfigint.h)
  configure_file(${dir}/jversion.h.in ${out}/jversion.h)
  tristim_read_source_list(listed ${dir} CMakeLists.txt "set\\(JPEG_SOURCES [^)]*\\)" "j[a-z0-9]+\\.c" 40 "libjpeg-turbo")
  set(jpeg_src ${listed} ${dir}/jaricom.c ${dir}/jcarith.c ${dir}/jdarith.c ${dir}/jsimd_none.c PARENT_SCOPE)
endfunction()
tristim_configure_libjpeg(${JPEG_DIR} ${CMAKE_BINARY_DIR}/third_party/jpeg)
tristim_wasm_library(jpeg_wasm INTERFACE_NAME tristim_jpeg SOURCES ${jpeg_src}
                     INCLUDES ${CMAKE_BINARY_DIR}/third_party/jpeg ${JPEG_DIR})

# --- libtiff 4.5: the core of libtiff/ and the codecs above; tif_config.h and tiffconf.h from
# its own CMake templates.
tristim_find_src(TIFF_DIR "tiff-4*" "libtiff")
function(tristim_configure_libtiff dir out)
  file(READ ${dir}/configure.ac tiff_ac)
  string(REGEX MATCH "LIBTIFF_MAJOR_VERSION=([0-9]+)" _ "${tiff_ac}")
  set(major ${CMAKE_MATCH_1})
  string(REGEX MATCH "LIBTIFF_MINOR_VERSION=([0-9]+)" _ "${tiff_ac}")
  set(minor ${CMAKE_MATCH_1})
  string(REGEX MATCH "LIBTIFF_MICRO_VERSION=([0-9]+)" _ "${tiff_ac}")
  set(PACKAGE_VERSION ${major}.${minor}.${CMAKE_MATCH_1})
  set(PACKAGE_NAME "LibTIFF Software")
  set(PACKAGE_STRING "${PACKAGE_NAME} ${PACKAGE_VERSION}")
  set(PACKAGE_TARNAME tiff)
  foreach(v CHECK_JPEG_YCBCR_SUBSAMPLING HAVE_ASSERT_H HAVE_FCNTL_H HAVE_FSEEKO HAVE_STRINGS_H
            HAVE_SYS_TYPES_H HAVE_UNISTD_H HAVE_IEEEFP JPEG_SUPPORT LZW_SUPPORT PACKBITS_SUPPORT
            ZIP_SUPPORT SUBIFD_SUPPORT DEFAULT_EXTRASAMPLE_AS_ALPHA STRIPCHOP_DEFAULT)
    set(${v} 1)
  endforeach()
  set(SIZEOF_SIZE_T 4)            # wasm32
  set(STRIP_SIZE_DEFAULT 8192)
  set(TIFF_MAX_DIR_COUNT 1048576)
  foreach(b 8 16 32 64)
    set(TIFF_INT${b}_T int${b}_t)
    set(TIFF_UINT${b}_T uint${b}_t)
  endforeach()
  set(TIFF_SSIZE_T int32_t)
  set(HOST_FILLORDER FILLORDER_LSB2MSB)
  set(HOST_BIG_ENDIAN 0)
  configure_file(${dir}/libtiff/tif_config.h.cmake.in ${out}/tif_config.h @ONLY)
  configure_file(${dir}/libtiff/tiffconf.h.cmake.in ${out}/tiffconf.h @ONLY)
endfunction()
tristim_configure_libtiff(${TIFF_DIR} ${CMAKE_BINARY_DIR}/third_party/tiff)
set(tiff_src "")
foreach(f aux close codec color compress dir dirinfo dirread dirwrite dumpmode error extension flush
          getimage hash_set jpeg lzw open packbits predict print read strip swab tile unix version
          warning write zip)
  list(APPEND tiff_src ${TIFF_DIR}/libtiff/tif_${f}.c)
endforeach()
tristim_wasm_library(tiff_wasm INTERFACE_NAME tristim_tiff SOURCES ${tiff_src}
                     INCLUDES ${CMAKE_BINARY_DIR}/third_party/tiff ${TIFF_DIR}/libtiff LINKS jpeg_wasm zlib_wasm)

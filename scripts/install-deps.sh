#!/usr/bin/env bash
# Installs everything tristim needs on a fresh Debian 12 machine (run as root).
# Idempotent: a second run only checks. Source packages (LibRaw, lcms2, NLopt, zlib, libpng,
# libjpeg-turbo, libtiff) are fetched from Debian's archive into third_party/ (git-ignored) for
# the WebAssembly build, and LibRaw's and NLopt's for every build (CMakeLists.txt: Debian's
# libraw.so crashes on a fuzzed DNG; cmake/nlopt.cmake: the same optimiser steps natively and in
# wasm); none of their source is committed.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)

PKGS="build-essential cmake pkg-config dpkg-dev libeigen3-dev catch2 emscripten
chromium liblcms2-dev liblcms2-utils argyll python3-opencv
python3-numpy ca-certificates opencolorio-tools parallel libtiff-dev libpng-dev libjpeg-dev zlib1g-dev
clang rawtran-doc rawtherapee libimage-exiftool-perl libraw-bin"  # libraw-bin: dcraw_emu opens the lab's rendered DNGs (tests/core/lab); rawtherapee + libimage-exiftool-perl: the DCP export is rendered by rawtherapee-cli and listed by exiftool (tests/CMakeLists.txt); rawtran-doc: a Canon 30D CR2 the RAW tests decode (tests/data/SOURCES.md); clang + libFuzzer for scripts/fuzz.sh (also pulled in by emscripten)

missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "[deps] installing:$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

# deb-src entries derived from the machine's own sources (no mirror address is written here).
if ! grep -rqs '^Types:.*deb-src' /etc/apt/sources.list.d/ && ! grep -qs '^deb-src' /etc/apt/sources.list; then
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources \
      > /etc/apt/sources.list.d/tristim-src.sources
  elif [ -f /etc/apt/sources.list ]; then
    grep '^deb ' /etc/apt/sources.list | grep -v 'deb-src' | sed 's/^deb /deb-src /' \
      > /etc/apt/sources.list.d/tristim-src.list
  fi
  apt-get update -qq
fi

# Source packages for the wasm build.
mkdir -p "$here/third_party"
fetch_src() { # $1 package, $2 dir glob
  if ! ls -d "$here/third_party/"$2 >/dev/null 2>&1; then
    echo "[deps] fetching Debian source of $1"
    (cd "$here/third_party" && apt-get source -qq "$1/bookworm" >/dev/null 2>&1 || apt-get source -qq "$1" >/dev/null)
  fi
}
fetch_src libraw 'libraw-0*/'
fetch_src lcms2 'lcms2-2*/'
fetch_src nlopt 'nlopt-2*/'
fetch_src zlib 'zlib-1*/'
fetch_src libpng1.6 'libpng1.6-1*/'
fetch_src libjpeg-turbo 'libjpeg-turbo-2*/'
fetch_src tiff 'tiff-4*/'

# JS dependencies (pinned in package-lock.json).
if [ -f "$here/package.json" ]; then
  (cd "$here" && { [ -d node_modules ] && npm ls --silent >/dev/null 2>&1 || npm ci --no-audit --no-fund --silent; })
fi
echo "[deps] ok"

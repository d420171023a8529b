#!/usr/bin/env bash
# Installs what is missing, then builds natively (build/native) and to wasm (build/wasm,
# whose site/ folder is the static page).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

echo "[build] native"
cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/native -j"$jobs"

echo "[build] wasm"
export NODE_PATH=/usr/share/nodejs   # emcc needs acorn (Debian's emscripten finds acorn there)
if [ ! -f build/wasm/CMakeCache.txt ]; then
  # The test emulator is plain node: emcmake's default adds a flag node 20 rejects.
  emcmake cmake -S . -B build/wasm -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CROSSCOMPILING_EMULATOR="$(command -v node)" >/dev/null
fi
cmake --build build/wasm -j"$jobs"
echo "[build] ok: CLI build/native/core/tristim, site build/wasm/site"

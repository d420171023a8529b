#!/usr/bin/env bash
# Builds everything, then runs every test: native ctest, wasm ctest (the same Catch2 suite under
# node), node --test for the wasm module, and the browser tests in Debian's Chromium.
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh || { echo "[test] build failed"; exit 1; }
status=0
jobs=$(nproc)

echo "[test] native ctest"
ctest --test-dir build/native --output-on-failure -j"$jobs" || status=1
echo "[test] wasm ctest"
ctest --test-dir build/wasm --output-on-failure -j"$jobs" || status=1
echo "[test] node --test (wasm module)"
node --test tests/wasm/ || status=1
echo "[test] browser (playwright-core + Chromium)"
node --test --test-concurrency=1 tests/web/ || status=1
# libFuzzer, every parser, FUZZ_SECONDS each (scripts/fuzz.sh; clang build in build/fuzz, LibRaw
# with the sanitizers): a crash fails the run.
echo "[test] fuzz (short run)"
FUZZ_SECONDS=${FUZZ_SECONDS:-20} bash scripts/fuzz.sh short || status=1

if [ $status -eq 0 ]; then echo "[test] all suites passed"; else echo "[test] FAILED"; fi
exit $status

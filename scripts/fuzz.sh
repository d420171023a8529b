#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with Debian's clang (address + undefined sanitizers on
# the whole core) into build/fuzz and runs each on its committed seed corpus.
#   scripts/fuzz.sh            short run: FUZZ_SECONDS (default 60) per target (CI)
#   scripts/fuzz.sh long       long run: FUZZ_RUNS (default 10000000) executions per target, with
#                              -timeout=1800; FUZZ_FORK=2 spreads one run over two processes
#                              (libFuzzer's fork mode; the total is the last "#N:" line)
# FUZZ_TARGETS="raw jpeg" runs only those targets; FUZZ_MAX_LEN (default 65536) caps input size.
# New inputs found go to build/fuzz/corpus/<target> (not committed); crashes to build/fuzz/crashes.
# Exit status 1 if any target crashed. LibRaw is compiled from its Debian source package with the
# same sanitizers (fuzz_raw); lcms2, NLopt, libtiff, libpng, libjpeg and zlib are Debian's
# uninstrumented builds here.
# A crash found: fix it, then commit the input as tests/fuzz/corpus/<target>/crash-<name> — the
# native ctest replays every corpus file (native:fuzz-replay:<target>), and so does ctest here
# (fuzz:<target>:seeds, under the sanitizers), before each run.
set -uo pipefail
cd "$(dirname "$0")/.."
mode=${1:-short}
out=build/fuzz
mkdir -p "$out"
# -O1 and line tables only: the usual libFuzzer build (stack traces with lines, a build ~2x faster
# than -O2 -g on 2 cores).
cmake -S . -B "$out" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" \
  -DTRISTIM_FUZZ=ON ${CCACHE:+-DCMAKE_CXX_COMPILER_LAUNCHER=ccache} > "$out.configure.log" 2>&1 \
  || { cat "$out.configure.log"; exit 1; }
cmake --build "$out" -j"$(nproc)" > "$out.build.log" 2>&1 || { tail -40 "$out.build.log"; exit 1; }
# UBSan: fatal, with the listed findings inside LibRaw suppressed (tests/fuzz/ubsan_suppressions.txt).
# FUZZ_LIBRAW_UB=report: LibRaw's undefined behaviour (its checks are recoverable) is printed, once
# per site and process, and the run goes on; tristim's own (-fno-sanitize-recover) and every
# AddressSanitizer error stay fatal. For long runs of fuzz_raw, which LibRaw's undefined behaviour
# otherwise stops every ~1 M executions; the sites printed are listed at the end.
halt=1
[ "${FUZZ_LIBRAW_UB:-}" = report ] && halt=0
export UBSAN_OPTIONS="halt_on_error=$halt:print_stacktrace=1:suppressions=$PWD/tests/fuzz/ubsan_suppressions.txt"
mkdir -p "$out/crashes"
status=0
echo "[fuzz] replaying the committed corpora (seeds and past crashes) under the sanitizers"
ctest --test-dir "$out" --output-on-failure -j"$(nproc)" > "$out.replay.log" 2>&1 \
  || { grep -E "Failed|ERROR|SUMMARY" "$out.replay.log" | head -20; status=1; }
for bin in "$out"/tests/fuzz/fuzz_*; do
  [ -x "$bin" ] || continue
  name=$(basename "$bin")
  seeds=tests/fuzz/corpus/${name#fuzz_}
  work="$out/corpus/${name#fuzz_}"
  mkdir -p "$work"
  # The short run starts from a fixed seed (-seed=1), so that a CI run is repeatable as far as a
  # time limit allows.
  if [ -n "${FUZZ_TARGETS:-}" ] && [[ " $FUZZ_TARGETS " != *" ${name#fuzz_} "* ]]; then continue; fi
  # A long run's -timeout is the wall clock of one input: a fuzzer starved by other work for longer
  # than 10 s would report a false timeout.
  if [ "$mode" = long ]; then limit="-runs=${FUZZ_RUNS:-10000000} -timeout=1800 ${FUZZ_FORK:+-fork=$FUZZ_FORK}"
  else limit="-max_total_time=${FUZZ_SECONDS:-60} -seed=1 -timeout=10"; fi
  echo "[fuzz] $name ($mode)"
  "$bin" "$work" "$seeds" $limit -max_len="${FUZZ_MAX_LEN:-65536}" -rss_limit_mb=2048 \
    -artifact_prefix="$out/crashes/$name-" -print_final_stats=1 > "$out/$name.log" 2>&1
  rc=$?
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$out/$name.log" | sed "s/^/[fuzz] $name /"
  grep -E "^#[0-9]+: cov" "$out/$name.log" | tail -1 | sed "s/^/[fuzz] $name fork mode, in all: /"
  grep -oE "[^ ]*libraw[^ ]*: runtime error: .*" "$out/$name.log" | sort -u | sed "s/^/[fuzz] $name LibRaw undefined behaviour (reported): /"
  if [ $rc -ne 0 ]; then status=1; echo "[fuzz] $name FAILED (exit $rc):"; grep -E "ERROR|SUMMARY|Test unit written" "$out/$name.log" | head -5; fi
done
if [ $status -eq 0 ]; then echo "[fuzz] no crashes"; else echo "[fuzz] crashes in $out/crashes"; fi
exit $status

#!/usr/bin/env bash
# Runs every benchmark (tests/bench/bench_*.cpp) natively and in wasm under node, in one run, and
# prints both times side by side with their ratio and the peak memory (native RSS, wasm heap).
# wasm runs twice: as node (and Chromium) run it, baseline code (Liftoff) first and optimised code
# (TurboFan) once a function is hot ("wasm ms"), and with `node --no-liftoff
# --no-wasm-lazy-compilation`, optimised code only, every function compiled at instantiation
# ("opt ms": the code quality, i.e. the steady state of a page in use; its first-call rows leave
# out the compile).
# Builds only the benchmark targets (assumes build/native and build/wasm were configured, e.g.
# by scripts/build.sh). Figures are printed, never asserted. Optional: dcraw_emu (Debian package
# libraw-bin) timings on the real RAW files, for scale.
# Each program runs BENCH_RUNS times (default 3) in each mode, the modes interleaved (native, wasm,
# opt, native, …), and every row prints the median: a row is often a single first call (decode,
# fresh memory), which one run's noise on a busy 2-core machine moves by 1.5×.
# usage: scripts/bench.sh [topic...]   e.g. `scripts/bench.sh detect` runs only bench_detect;
#        BENCH_RUNS=1 scripts/bench.sh   one run of each (quicker, noisier).
set -uo pipefail
cd "$(dirname "$0")/.."
export NODE_PATH=/usr/share/nodejs
names=$(ls tests/bench/bench_*.cpp 2>/dev/null | xargs -n1 basename | sed 's/\.cpp$//')
if [ $# -gt 0 ]; then
  wanted=$(printf 'bench_%s\n' "${@#bench_}")
  names=$(printf '%s\n' $names | grep -Fx "$wanted")
fi
[ -n "$names" ] || { echo "[bench] no tests/bench/bench_*.cpp"; exit 0; }
runs=${BENCH_RUNS:-3}
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "[bench] BENCH_RUNS must be a positive integer (got '$runs')"; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for n in $names; do
  echo "[bench] building $n (native, wasm)"
  cmake --build build/native --target "$n" -j2 >"$tmp/build.log" 2>&1 || { tail -20 "$tmp/build.log"; exit 1; }
  cmake --build build/wasm --target "$n" -j2 >"$tmp/build.log" 2>&1 || { tail -20 "$tmp/build.log"; exit 1; }
done

for n in $names; do
  native=build/native/tests/bench/$n
  wasm=build/wasm/tests/bench/$n.cjs
  echo
  echo "=== $n ==="
  for r in $(seq 1 "$runs"); do
    "$native" >"$tmp/native.$r" 2>&1 || echo "[bench] $n native exited $?"
    node "$wasm" >"$tmp/wasm.$r" 2>&1 || echo "[bench] $n wasm exited $?"
    node --no-liftoff --no-wasm-lazy-compilation "$wasm" >"$tmp/opt.$r" 2>&1 || echo "[bench] $n wasm optimised-only exited $?"
  done
  files=()
  for mode in native wasm opt; do for r in $(seq 1 "$runs"); do files+=("$tmp/$mode.$r"); done; done
  if grep -q '^BENCH ' "$tmp/native.1"; then
    grep '^CASE ' "$tmp/native.1" | sed 's/^CASE /  /'
    echo "  (median of $runs runs per mode)"
    # Join "BENCH case step ms" lines of the three modes (median over the runs of each); "PEAK case
    # MiB" lines give memory.
    awk -v runs="$runs" '
      function ratio(a, b) { return (a > 0 && b != "") ? sprintf("%.2f", b / a) : "-" }
      function median(m, key,    c, i, j, v, t) {
        c = cnt[m, key]
        if (c == 0) return ""
        for (i = 1; i <= c; i++) v[i] = val[m, key, i] + 0
        for (i = 2; i <= c; i++) for (j = i; j > 1 && v[j - 1] > v[j]; j--) { t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
        return c % 2 ? v[(c + 1) / 2] : (v[c / 2] + v[c / 2 + 1]) / 2
      }
      FNR == 1 { file++; mode = int((file - 1) / runs) + 1 }
      $1 == "BENCH" { key = $2 " " $3; val[mode, key, ++cnt[mode, key]] = $4
                      if (!(key in seen)) { seen[key] = 1; order[++k] = key } }
      $1 == "PEAK" { key = "peak " $2; val[mode, key, ++cnt[mode, key]] = $3 }
      ($1 == "ERROR" || $1 == "SKIP") && mode < 3 && (file - 1) % runs == 0 { print "  " (mode == 1 ? "native: " : "wasm: ") $0 }
      END {
        printf "  %-22s %-18s %11s %11s %7s %11s %7s\n", "case", "step", "native ms", "wasm ms", "ratio", "opt ms", "ratio"
        for (i = 1; i <= k; i++) {
          split(order[i], a, " ")
          n = median(1, order[i]); w = median(2, order[i]); o = median(3, order[i])
          printf "  %-22s %-18s %11s %11s %7s %11s %7s\n", a[1], a[2], n, (w == "" ? "-" : w), ratio(n, w), (o == "" ? "-" : o), ratio(n, o)
          if (a[2] == "total") { np = median(1, "peak " a[1]); wp = median(2, "peak " a[1])
            printf "  %-22s %-18s %11s %11s\n", a[1], "peak MiB (RSS/heap)", np, (wp == "" ? "-" : wp) }
        }
      }' "${files[@]}"
  else
    for r in $(seq 1 "$runs"); do
      echo "--- native (run $r)"; cat "$tmp/native.$r"
      echo "--- wasm (node, run $r)"; cat "$tmp/wasm.$r"
      echo "--- wasm (node --no-liftoff --no-wasm-lazy-compilation: optimised code only, run $r)"; cat "$tmp/opt.$r"
    done
  fi
done

if command -v dcraw_emu >/dev/null; then
  echo
  echo "=== for scale: LibRaw dcraw_emu -h (half-size, native) ==="
  # The same files as bench_raw (tests/support/test_files.hpp).
  for f in examples/web/passport.dng /usr/share/doc/rawtran/IMG_5952.CR2; do
    [ -f "$f" ] || { echo "[bench] $f not found (scripts/install-deps.sh installs it)"; exit 1; }
    s=$(date +%s%N); dcraw_emu -h -Z - "$f" >/dev/null 2>&1; e=$(date +%s%N)
    printf "  %-60s %8.1f ms\n" "$(basename "$f")" "$(echo "($e - $s) / 1000000" | bc -l)"
  done
else
  echo "(dcraw_emu not installed: apt-get install libraw-bin for LibRaw's own timing)"
fi

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
# usage: scripts/bench.sh [topic...]   e.g. `scripts/bench.sh detect` runs only bench_detect.
set -uo pipefail
cd "$(dirname "$0")/.."
export NODE_PATH=/usr/share/nodejs
shared=${TRISTIM_SHARED_DATA:-$(cd .. && pwd)/shared/data}
names=$(ls tests/bench/bench_*.cpp 2>/dev/null | xargs -n1 basename | sed 's/\.cpp$//')
if [ $# -gt 0 ]; then
  wanted=$(printf 'bench_%s\n' "${@#bench_}")
  names=$(printf '%s\n' $names | grep -Fx "$wanted")
fi
[ -n "$names" ] || { echo "[bench] no tests/bench/bench_*.cpp"; exit 0; }
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
  TRISTIM_SHARED_DATA="$shared" "$native" >"$tmp/native.txt" 2>&1 || echo "[bench] $n native exited $?"
  TRISTIM_SHARED_DATA="$shared" node "$wasm" >"$tmp/wasm.txt" 2>&1 || echo "[bench] $n wasm exited $?"
  TRISTIM_SHARED_DATA="$shared" node --no-liftoff --no-wasm-lazy-compilation "$wasm" >"$tmp/opt.txt" 2>&1 || echo "[bench] $n wasm optimised-only exited $?"
  if grep -q '^BENCH ' "$tmp/native.txt"; then
    grep '^CASE ' "$tmp/native.txt" | sed 's/^CASE /  /'
    # Join "BENCH case step ms" lines of both runs; "PEAK case MiB" lines give memory.
    awk '
      function ratio(a, b) { return (a > 0 && b != "") ? sprintf("%.2f", b / a) : "-" }
      FNR == 1 { file++ }
      $1 == "BENCH" { key = $2 " " $3; if (file == 1) nat[key] = $4; else if (file == 2) was[key] = $4; else opt[key] = $4
                      if (!(key in seen)) { seen[key] = 1; order[++k] = key } }
      $1 == "PEAK" { if (file == 1) npk[$2] = $3; else if (file == 2) wpk[$2] = $3 }
      ($1 == "ERROR" || $1 == "SKIP") && file < 3 { print "  " (file == 1 ? "native: " : "wasm: ") $0 }
      END {
        printf "  %-22s %-18s %11s %11s %7s %11s %7s\n", "case", "step", "native ms", "wasm ms", "ratio", "opt ms", "ratio"
        for (i = 1; i <= k; i++) {
          split(order[i], a, " ")
          n = nat[order[i]]; w = was[order[i]]; o = opt[order[i]]
          printf "  %-22s %-18s %11s %11s %7s %11s %7s\n", a[1], a[2], n, (w == "" ? "-" : w), ratio(n, w), (o == "" ? "-" : o), ratio(n, o)
          if (a[2] == "total") printf "  %-22s %-18s %11s %11s\n", a[1], "peak MiB (RSS/heap)", npk[a[1]], (wpk[a[1]] == "" ? "-" : wpk[a[1]])
        }
      }' "$tmp/native.txt" "$tmp/wasm.txt" "$tmp/opt.txt"
  else
    echo "--- native"; cat "$tmp/native.txt"
    echo "--- wasm (node)"; cat "$tmp/wasm.txt"
    echo "--- wasm (node --no-liftoff --no-wasm-lazy-compilation: optimised code only)"; cat "$tmp/opt.txt"
  fi
done

if command -v dcraw_emu >/dev/null; then
  echo
  echo "=== for scale: LibRaw dcraw_emu -h (half-size, native) ==="
  for f in raw-images/tinydng/colorchart_canon_eos_kiss_x4_magiclantern_colorchecker_passport.dng \
           raw-images/debian-rawtran-doc/IMG_5952_canon_eos_30d.CR2; do
    [ -f "$shared/$f" ] || continue
    s=$(date +%s%N); dcraw_emu -h -Z - "$shared/$f" >/dev/null 2>&1; e=$(date +%s%N)
    printf "  %-60s %8.1f ms\n" "$(basename "$f")" "$(echo "($e - $s) / 1000000" | bc -l)"
  done
else
  echo "(dcraw_emu not installed: apt-get install libraw-bin for LibRaw's own timing)"
fi

#!/usr/bin/env bash
# The batch path (issue 13, examples/batch): GNU parallel runs `tristim sample` and `tristim apply`
# over a folder. Every good file gives the same result as a serial run of the same command, every
# bad file leaves its coded error in errors.log with its name, and the batch says it failed.
# usage: batch_check.sh <tristim> <example.dng> <work-dir>
set -euo pipefail
tristim=$1 dng=$2 work=$3
batch=$(cd "$(dirname "$0")/../../examples/batch" && pwd)/batch.sh
rm -rf "$work"; mkdir -p "$work/in"
for i in 1 2 3; do cp "$dng" "$work/in/shot $i.dng"; done
head -c 5000 "$dng" > "$work/in/truncated.dng"
echo "a text file renamed .CR2" > "$work/in/text.CR2"
fail() { echo "FAIL: $*"; exit 1; }

rc=0; TRISTIM=$tristim JOBS=2 bash "$batch" sample "$work/in" "$work/csv" --chart passport || rc=$?
[ "$rc" -eq 1 ] || fail "sample batch with two bad files should exit 1, got $rc"
for i in 1 2 3; do
  "$tristim" sample "$work/in/shot $i.dng" --chart passport > "$work/serial.csv" 2>/dev/null
  cmp -s "$work/serial.csv" "$work/csv/shot $i.csv" || fail "shot $i.csv differs from a serial run"
  [ "$(wc -l < "$work/csv/shot $i.csv")" -eq 25 ] || fail "shot $i.csv should have 24 patches"
done
grep -q '^truncated.dng:.*error RAW_TRUNCATED' "$work/csv/errors.log" || fail "no RAW_TRUNCATED line for truncated.dng"
grep -q '^text.CR2:.*error RAW_UNSUPPORTED' "$work/csv/errors.log" || fail "no RAW_UNSUPPORTED line for text.CR2"
[ ! -e "$work/csv/truncated.csv" ] && [ ! -e "$work/csv/text.csv" ] || fail "a failed file left a partial CSV"
[ "$(grep -c . "$work/csv/errors.log")" -eq 2 ] || fail "errors.log should hold exactly the two failures"

"$tristim" reference --chart passport --illuminant D50 > "$work/ref.csv"
"$tristim" fit --rgb "$work/csv/shot 1.csv" --xyz "$work/ref.csv" --model Finlayson2015-2 --objective ls --no-loo --out "$work/p.json"
rm -f "$work/in/truncated.dng" "$work/in/text.CR2"
TRISTIM=$tristim JOBS=2 bash "$batch" apply "$work/p.json" "$work/in" "$work/xyz"
for i in 1 2 3; do
  "$tristim" apply "$work/p.json" "$work/in/shot $i.dng" --out "$work/serial.tiff" 2>/dev/null
  cmp -s "$work/serial.tiff" "$work/xyz/shot $i.tiff" || fail "shot $i.tiff differs from a serial run"
done
[ ! -s "$work/xyz/errors.log" ] || fail "errors.log should be empty: $(cat "$work/xyz/errors.log")"
echo "batch: sample and apply over a folder with GNU parallel = serial runs; bad files reported with their codes"

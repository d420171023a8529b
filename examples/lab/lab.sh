#!/usr/bin/env bash
# The colorimetry lab from the command line (issue 45): render a ColorChecker photographed by a
# camera of the 52 as a real DNG, run it through the normal journey (detect, sample, reference,
# fit, evaluate) and compare with the renderer's truth; then camera quality, the exercises and metamers.
#   bash examples/lab/lab.sh [path/to/tristim] [output dir]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
T=${1:-$here/build/native/core/tristim}
out=${2:-$(mktemp -d)}
mkdir -p "$out"
cam="Nikon_D850"

echo "== render: $cam, ColorChecker Classic, D50, no noise"
"$T" lab render --camera "$cam" --chart cc24 --illuminant D50 --exposure 0.6 --out "$out/chart.dng" > "$out/truth.json"
echo "== the journey on the rendered DNG"
"$T" detect "$out/chart.dng" --chart cc24 > "$out/detect.json"
"$T" sample "$out/chart.dng" --chart cc24 > "$out/patches.csv" 2>/dev/null
"$T" reference --chart cc24 --illuminant D50 > "$out/reference.csv"
"$T" fit --rgb "$out/patches.csv" --xyz "$out/reference.csv" --model matrix-3x3 --out "$out/p.json" > /dev/null
"$T" evaluate --profile "$out/p.json" --rgb "$out/patches.csv" --xyz "$out/reference.csv" > "$out/evaluate.json"
echo "== sampled camera RGB vs the renderer's truth (worst |difference|, DN)"
python3 - "$out/truth.json" "$out/patches.csv" <<'PY'
import csv, json, sys
truth = {p["id"]: p["rgb"] for p in json.load(open(sys.argv[1]))["patches"]}
worst = max(abs(float(r[c]) - truth[r["patch"]][i]) for r in csv.DictReader(open(sys.argv[2])) for i, c in enumerate("RGB"))
print(f"worst {worst:g} DN (noise off: 0)")
sys.exit(0 if worst <= 1e-6 else 1)
PY
echo "== a chart of one's own: Munsell chips (two chips and the 5PB hue page) as a grid, sampled as its truth says"
"$T" lab render --camera "$cam" --chart munsell:5R4/14,10YR6/10,5PB --illuminant D50 --out "$out/chips.dng" > "$out/chips.json"
# shellcheck disable=SC2046  # the truth's sample_args are several options
"$T" sample "$out/chips.dng" $(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["sample_args"])' "$out/chips.json") > "$out/chips.csv"
python3 - "$out/chips.json" "$out/chips.csv" <<'PY'
import csv, json, sys
truth = {p["cell"]: p for p in json.load(open(sys.argv[1]))["patches"]}
rows = [r for r in csv.DictReader(open(sys.argv[2])) if r["patch"] in truth]
worst = max(abs(float(r[c]) - truth[r["patch"]]["rgb"][i]) for r in rows for i, c in enumerate("RGB"))
print(f"{len(rows)} chips, worst {worst:g} DN (noise off: 0)")
sys.exit(0 if worst <= 1e-6 and len(rows) == len(truth) else 1)
PY
echo "== camera quality: SMI and mu of this camera, and the best five of the 52"
"$T" lab smi --camera "$cam" --json
"$T" lab smi > "$out/smi.csv" && head -6 "$out/smi.csv"
echo "== exercise 1: a patch under three lights (the reference step's numbers)"
for ill in D65 A F11; do "$T" reference --chart cc24 --illuminant "$ill" --observer 1931 | grep '^C3,' | sed "s/^/$ill: /"; done
echo "== exercise 2: why a 3x3 is not enough"
"$T" lab overfit --camera "$cam"
echo "== metamerism: Munsell pairs matching under D65, apart under A; a metamer of 5R5/6 made for the eye, seen by the camera"
"$T" lab metamers --illuminant D65 --second A --max-match 0.5 --top 3
"$T" lab metamers --illuminant D65 --second F11 --camera "$cam" --construct 5R5/6
echo "(files in $out)"

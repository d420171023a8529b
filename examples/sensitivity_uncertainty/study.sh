#!/bin/sh
# The sensitivity-estimate uncertainty study, with the CLI: each built-in camera held out of the
# basis (--exclude), a virtual ColorChecker photograph under D65 (tristim simulate, linear RGB,
# optional noise), its sensitivities estimated (Jiang et al. 2013, K = 4) with the stated
# uncertainty of A_R/A_G and A_B/A_G, compared with the camera's own curves (--compare). Prints a
# Markdown row per camera (error vs stated band, inside or not, residual, nearest basis camera,
# warnings) and the coverage. The table in docs/methods.md is this script's output.
#   sh examples/sensitivity_uncertainty/study.sh [tristim binary] [noise σ] [number of cameras]
set -eu
T=${1:-build/native/core/tristim}
NOISE=${2:-0}
LIMIT=${3:-1000}
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
"$T" list --what cameras | awk -F, 'NR > 1 { print $2 }' | head -n "$LIMIT" > "$DIR/cameras"
echo "| held-out camera | A_R/A_G error | stated ±u | inside | A_B/A_G error | stated ±u | inside | residual | nearest (RMS) | warnings |"
echo "|---|---|---|---|---|---|---|---|---|---|"
while read -r cam; do
  "$T" simulate --camera "$cam" --reflectances cc24 --illuminant D65 --noise "$NOISE" --seed 11 > "$DIR/rgb.csv"
  "$T" sensitivities estimate --rgb "$DIR/rgb.csv" --reflectances cc24 --illuminant D65 --exclude "$cam" \
      --compare "$cam" --out "$DIR/ssf.csv" 2> /dev/null > "$DIR/$cam.json"
done < "$DIR/cameras"
python3 - "$DIR" "$NOISE" << 'PY'
import json, sys, os
d, noise = sys.argv[1], sys.argv[2]
inside = n = warned = 0
for cam in open(os.path.join(d, "cameras")).read().split():
    s = json.load(open(os.path.join(d, cam + ".json")))
    u, c = s["uncertainty"], s["compare"]
    row, w = [], u["warnings"]
    for i, k in enumerate(("area_ratio_R_G", "area_ratio_B_G")):
        err = s[k] / c[k] - 1
        ok = abs(err) <= u["u"][i]
        inside += ok; n += 1
        row += ["%+.2f %%" % (100 * err), "%.2f %%" % (100 * u["u"][i]), "yes" if ok else "no"]
    warned += bool(w)
    print("| %s | %s | %.2f %% | %.3f | %s |" % (cam, " | ".join(row), 100 * s["residual_rms"], u["nearest_distance"], " ".join(w) or "-"))
print("\nCoverage (noise %s, k = %g): %d of %d ratios inside their stated band (%.0f %%); %d cameras warned"
      % (noise, u["coverage"], inside, n, 100.0 * inside / n, warned))
PY

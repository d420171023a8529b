#!/usr/bin/env bash
# The absolute tele-colorimeter end to end on a virtual bracketed series (see README.md).
# Needs a native build (scripts/build.sh): build/native/core/tristim and build/native/tests/absolute_fixture.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$root/build/native
out=${1:-$(mktemp -d)}
"$bin/tests/absolute_fixture" "$out"
cd "$out"
t="$bin/core/tristim"
echo "== sensitivities estimated from one ColorChecker photo (Canon 5D Mark II left out of the basis)"
"$t" sensitivities estimate --rgb patches_rgb.csv --reflectances cc24 --illuminant D65 \
    --exclude Canon_EOS_5D_Mark_II --compare Canon_EOS_5D_Mark_II --out ssf_estimated.csv
echo "== fit: lens cap, flat, 155 luminance stimuli at 5 exposures, 24 projected colours"
"$t" absolute fit --stimuli stimuli.csv --dark cap_1.dng --dark cap_2.dng --flat flat.dng \
    --ssf ssf_estimated.csv --out profile.json
echo "== apply: five exposures fused, XYZ TIFF in cd/m2 and the source-exposure map"
"$t" absolute apply profile.json scene_1.dng scene_2.dng scene_3.dng scene_4.dng scene_5.dng \
    --out xyz.tiff --source-map source.tiff --points scene_truth.csv
echo "== evaluate: the scene as a test scene (regions of the bracket and per-patch rows), section 4.1 figures"
"$t" absolute evaluate profile.json --stimuli scene_test.csv --white D1 scene_1.dng scene_2.dng scene_3.dng scene_4.dng scene_5.dng \
    | sed -n '/^test, /,/^$/p'
echo "outputs in $out"

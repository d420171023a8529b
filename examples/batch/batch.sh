#!/usr/bin/env bash
# Runs one tristim command over every file of a folder with GNU parallel (Debian package
# `parallel`). `tristim apply` and `tristim sample` are pure per-file commands: one file in, one
# file out, nothing shared, so the same line scales from a laptop's cores to a cluster's nodes
# (see README.md here for a Kubernetes Job and a Ray map). No scheduler of our own.
#
#   batch.sh apply  <profile.json> <input-folder> <output-folder>          -> <name>.tiff (float XYZ)
#   batch.sh sample <input-folder> <output-folder> --chart <id> [sample options]  -> <name>.csv
#
# Every file is tried; a file that fails leaves its one-line coded error in <output>/errors.log
# (prefixed with the file's name) and the others still run. <output>/joblog.tsv is parallel's
# job log (one row per file: exit status, run time). Exit status: 0 when every file succeeded,
# 1 when some failed, 2 for a usage error. JOBS=N limits the parallel jobs (default: one per core);
# TRISTIM=path chooses the binary (default: this checkout's build/native/core/tristim).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tristim=${TRISTIM:-$here/../../build/native/core/tristim}
usage() { sed -n '7,8p' "$0" | sed 's/^# *//' >&2; exit 2; }
[ $# -ge 1 ] || usage
command -v parallel >/dev/null || { echo "batch.sh: GNU parallel is not installed (apt-get install parallel)" >&2; exit 2; }
[ -x "$tristim" ] || { echo "batch.sh: $tristim not found: build first (bash scripts/build.sh)" >&2; exit 2; }

mode=$1; shift
q() { printf '%q ' "$@"; }
case "$mode" in
  apply)  [ $# -eq 3 ] || usage; profile=$1 in=$2 out=$3
          [ -f "$profile" ] || { echo "batch.sh: profile $profile not found" >&2; exit 2; }
          result='{/.}.tiff'
          run="$(q "$tristim" apply "$profile") {} --out $(printf %q "$out")/$result" ;;
  sample) [ $# -ge 2 ] || usage; in=$1 out=$2; shift 2
          result='{/.}.csv'
          run="$(q "$tristim" sample) {} $(q "$@") > $(printf %q "$out")/$result" ;;
  *) usage ;;
esac
[ -d "$in" ] || { echo "batch.sh: input folder $in not found" >&2; exit 2; }
mkdir -p "$out"
: > "$out/errors.log"
mapfile -d '' files < <(find "$in" -maxdepth 1 -type f ! -name '.*' -print0 | sort -z)
[ ${#files[@]} -gt 0 ] || { echo "batch.sh: no files in $in" >&2; exit 2; }

# One job per file: its stderr is kept only when it fails (then with the file's name in front,
# --tagstring), and a failed job leaves no partial result behind. --halt never: every file is tried.
o=$(printf %q "$out")
job="$run 2> $o/.{/.}.err && rm -f $o/.{/.}.err || { cat $o/.{/.}.err >&2; rm -f $o/.{/.}.err $o/$result; exit 1; }"
printf '%s\0' "${files[@]}" | parallel -0 --jobs "${JOBS:-100%}" --halt never --joblog "$out/joblog.tsv" \
  --tagstring '{/}:' "$job" 2>> "$out/errors.log" >/dev/null || true
failed=$(awk -F'\t' 'NR > 1 && $7 != 0' "$out/joblog.tsv" | wc -l)
echo "batch.sh $mode: ${#files[@]} files, $(( ${#files[@]} - failed )) done, $failed failed -> $out"
[ "$failed" -eq 0 ] || { echo "batch.sh: errors in $out/errors.log" >&2; exit 1; }

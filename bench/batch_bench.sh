#!/usr/bin/env bash
# A batch against separate runs: remeshes the same scans once as one
# `geodual remesh A B ... --output-dir` and once as one `geodual remesh A -o`
# per scan, one after the other in the same run of this script, and prints
# the wall time and peak memory of each (GNU time), and whether every output
# has the same bytes both ways. Run from the repository root after building:
#
#   bench/batch_bench.sh [remesh options, e.g. --sites 2000 --samples -1]
#
# The scans are tests/data/*.ply (set GEODUAL_BATCH_SCANS to a list of paths
# to use others); the default options are the remesh's own.
set -euo pipefail
geodual=${GEODUAL_CLI:-build/geodual}
read -r -a scans <<<"${GEODUAL_BATCH_SCANS:-$(ls tests/data/*.ply | head -n 10 | tr '\n' ' ')}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/batch" "$work/single"

measure() {  # label, command...: prints "label  wall s  peak MiB"
  local label=$1
  shift
  /usr/bin/time -f "%e %M" -o "$work/time" "$@" >/dev/null 2>"$work/stderr" || {
    cat "$work/stderr" >&2
    return 1
  }
  read -r seconds kilobytes <"$work/time"
  printf '%-28s %9.1f s %9.0f MiB\n' "$label" "$seconds" "$((kilobytes / 1024))"
}

echo "${#scans[@]} scans, options: ${*:-(defaults)}; $(nproc) cores"
measure "batch (--output-dir)" "$geodual" remesh "${scans[@]}" --output-dir "$work/batch" --quiet "$@"
start=$(date +%s%N)
peak=0
for scan in "${scans[@]}"; do
  out="$work/single/$(basename "${scan%.*}").glb"
  /usr/bin/time -f "%M" -o "$work/time" "$geodual" remesh "$scan" -o "$out" --quiet "$@" >/dev/null 2>&1
  kilobytes=$(<"$work/time")
  ((kilobytes > peak)) && peak=$kilobytes
done
end=$(date +%s%N)
milliseconds=$(((end - start) / 1000000))
printf '%-28s %7d.%01d s %9.0f MiB (largest run)\n' "${#scans[@]} separate runs" "$((milliseconds / 1000))" \
  "$((milliseconds % 1000 / 100))" "$((peak / 1024))"
if diff -r "$work/batch" "$work/single" >/dev/null; then
  echo "outputs: the same bytes"
else
  echo "outputs: DIFFER" && exit 1
fi

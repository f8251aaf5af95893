#!/usr/bin/env bash
# Figures for `geodual info`: wall time and peak memory of the whole command
# (median of 5 runs of /usr/bin/time -v), file size, and read throughput (file
# bytes over the read time the tool reports), on MESH and on MESH Loop-subdivided
# once (four times the faces, float64 as written by geodual::io::write_ply).
# The README's figures are for igea.ply (268,686 faces, float32; the team's
# larger scans, not in the repository). With --profile, also a perf profile of
# one run on the larger file.
#
# usage: bench/info_figures.sh [--profile] [MESH [BUILD_DIR]]   (from the repository root;
#        MESH defaults to examples/data/bunny.ply, BUILD_DIR to build, which must
#        hold geodual and bench/make_subdivided)
set -euo pipefail

profile=false
if [[ "${1:-}" == "--profile" ]]; then
  profile=true
  shift
fi
mesh=${1:-examples/data/bunny.ply}
build=${2:-build}
runs=5
geodual=$build/geodual
cache=$build/bench-data

for tool in "$geodual" "$build/bench/make_subdivided" /usr/bin/time; do
  [[ -x "$tool" ]] || { echo "info_figures: $tool not found (build the geodual and make_subdivided targets)" >&2; exit 1; }
done

mkdir -p "$cache"
subdivided=$cache/$(basename "$mesh" .ply)_loop1.ply
if [[ ! -f "$subdivided" ]]; then
  "$build/bench/make_subdivided" "$mesh" 1 "$subdivided"
fi

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
json_number() { sed -n "s/^ *\"$1\": \([-0-9.eE+]*\),\{0,1\}$/\1/p" "$2"; }

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

echo "geodual info figures: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), median of $runs runs"
printf '%-22s %10s %12s %10s %10s %10s %10s %12s\n' \
  file faces bytes "wall s" "peak MiB" "read s" "read MB/s" "analysis s"
for file in "$mesh" "$subdivided"; do
  "$geodual" info "$file" > /dev/null  # warm the page cache: the figures are for a file in memory
  : > "$scratch/wall"; : > "$scratch/rss"; : > "$scratch/read"; : > "$scratch/analysis"
  for ((run = 0; run < runs; ++run)); do
    /usr/bin/time -v "$geodual" info --json "$file" > "$scratch/out.json" 2> "$scratch/time.txt"
    # "Elapsed (wall clock) time (h:mm:ss or m:ss): 0:01.23"
    sed -n 's/.*Elapsed (wall clock) time.*: //p' "$scratch/time.txt" |
      awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; print s }' >> "$scratch/wall"
    sed -n 's/.*Maximum resident set size (kbytes): //p' "$scratch/time.txt" >> "$scratch/rss"
    json_number read_seconds "$scratch/out.json" >> "$scratch/read"
    json_number analysis_seconds "$scratch/out.json" >> "$scratch/analysis"
  done
  faces=$(json_number faces "$scratch/out.json")
  bytes=$(json_number file_bytes "$scratch/out.json")
  wall=$(median < "$scratch/wall")
  rss_kib=$(median < "$scratch/rss")
  read=$(median < "$scratch/read")
  analysis=$(median < "$scratch/analysis")
  awk -v name="$(basename "$file")" -v faces="$faces" -v bytes="$bytes" -v wall="$wall" -v rss="$rss_kib" \
      -v read="$read" -v analysis="$analysis" 'BEGIN {
    printf "%-22s %10d %12d %10.3f %10.1f %10.4f %10.0f %12.4f\n",
           name, faces, bytes, wall, rss / 1024, read, bytes / 1e6 / read, analysis }'
done

if $profile; then
  command -v perf > /dev/null || { echo "info_figures: perf not found" >&2; exit 1; }
  echo
  echo "perf profile of: geodual info $subdivided"
  perf record -q -g -o "$scratch/perf.data" "$geodual" info "$subdivided" > /dev/null 2>&1
  perf report -i "$scratch/perf.data" --no-children --stdio --percent-limit 1.5 2>/dev/null |
    grep -E '^ +[0-9.]+%' | cut -c1-160
fi

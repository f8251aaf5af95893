#!/usr/bin/env bash
# Runs every reader's libFuzzer target for SECONDS each (default 600), one
# after another, from the repository root, after the build in
# docs/development.md ("Fuzzing the mesh readers"). Seeds come from
# make_seed_corpus (PLY, OBJ, OFF, STL) and, for glTF, from any .gltf/.glb
# files under fuzz-corpus/seeds/gltf. Prints one line per target; findings
# land in fuzz-corpus/artifacts/ and the run's exit status is non-zero.
set -uo pipefail
seconds=${1:-600}
build=${GEODUAL_FUZZ_BUILD:-build-fuzz}
mkdir -p fuzz-corpus/artifacts fuzz-corpus/logs
if [[ ! -d fuzz-corpus/seeds/ply ]]; then
  "$build/fuzz/make_seed_corpus" fuzz-corpus/seeds tests/data/{woody,spot,bunny_res2}.ply examples/data/bunny.ply
fi
mkdir -p fuzz-corpus/seeds/gltf
status=0
for format in ply obj off stl gltf; do
  mkdir -p "fuzz-corpus/$format"
  dict=()
  [[ -f tests/fuzz/$format.dict ]] && dict=(-dict="tests/fuzz/$format.dict")
  log=fuzz-corpus/logs/$format.log
  "$build/fuzz/fuzz_$format" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=16384 \
    -print_final_stats=1 "${dict[@]}" -artifact_prefix="fuzz-corpus/artifacts/$format-" \
    "fuzz-corpus/$format" "fuzz-corpus/seeds/$format" >"$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  peak=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log" | grep -o '[0-9]*$')
  echo "$format: exit $rc, ${runs:-?} inputs in ${seconds} s, coverage ${cov:-?} edges, peak ${peak:-?} MB, corpus $(ls "fuzz-corpus/$format" | wc -l) files"
  ((rc == 0)) || status=1
done
ls fuzz-corpus/artifacts
exit $status

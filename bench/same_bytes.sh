#!/usr/bin/env bash
# Whether two geodual binaries write the same bytes: the remeshes a refactor
# must leave alone, through features, pins, sizing options, the repair and
# the weld (its rounds, retries, doubled points, cracks), run with each
# binary and compared byte for byte.
#
#   bench/same_bytes.sh OLD_BINARY NEW_BINARY   # from the repository root
#
# Prints one line per run ("same" or "DIFF") and exits 1 if any differs.
set -euo pipefail
old=$1
new=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
runs=(
  "bunny tests/data/bunny.ply --sites 1500"
  "bunny_curvature tests/data/bunny.ply --sites 1500 --curvature-adaptation 1"
  "fandisk tests/data/fandisk.ply --sites 2000"
  "fandisk_options tests/data/fandisk.ply --sites 2000 --no-fitting --smoothing-angle 20"
  "example001 tests/data/cad/example001.stl --sites 1000"
  "example001_pins tests/data/cad/example001.stl --sites 1000 --pin-creases"
  "sign tests/data/cad/sign.stl --sites 2000"
  "example013 tests/data/cad/example013.stl --sites 2000"
  "cheburashka tests/data/cheburashka.ply --sites 500"
  "text_on_cube tests/data/cad/text_on_cube.stl --sites 2000"
  "surface_image tests/data/cad/surface_image.stl --sites 500"
  "bunny_res2 tests/data/bunny_res2.ply --sites 2000"
  "example020 tests/data/cad/example020.stl --sites 2000"
  "horse tests/data/horse.ply --sites 1000"
  "letter_block tests/data/cad/LetterBlock.stl --sites 2000"
  "example016 tests/data/cad/example016.stl --sites 500"
  "cheburashka_300 tests/data/cheburashka.ply --sites 300"
)
status=0
for run in "${runs[@]}"; do
  read -r name mesh options <<<"$run"
  # shellcheck disable=SC2086  # the options are words
  "$old" remesh "$mesh" $options --samples -1 -q -o "$out/$name.old.ply" >/dev/null 2>&1 || true
  # shellcheck disable=SC2086
  "$new" remesh "$mesh" $options --samples -1 -q -o "$out/$name.new.ply" >/dev/null 2>&1 || true
  if [[ -f "$out/$name.old.ply" ]] && cmp -s "$out/$name.old.ply" "$out/$name.new.ply"; then
    echo "same $name"
  else
    echo "DIFF $name"
    status=1
  fi
done
exit $status

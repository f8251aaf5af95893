#!/usr/bin/env bash
# Remeshes every distinct triangulated surface that Debian's openfoam-examples
# package ships (CAD parts, terrain, soups with duplicates and non-manifold
# edges: meshes nobody tuned geodual for) with remesh_sweep, and prints its
# table. Run from the repository root after building remesh_sweep:
#
#   apt-get install openfoam-examples          # once, as root (about 36 MB)
#   bench/openfoam_sweep.sh [remesh_sweep options, e.g. --sites 2000 --time-limit 300]
#
# The files are decompressed into a temporary folder, named
# <example>-<file> (the example's folder and the file), and files with the
# same bytes are taken once.
set -euo pipefail
root=/usr/share/doc/openfoam-examples/examples
sweep=${GEODUAL_SWEEP:-build/bench/remesh_sweep}
if [[ ! -d $root ]]; then
  echo "openfoam_sweep: $root not found; install Debian's openfoam-examples" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
declare -A seen
meshes=()
while IFS= read -r -d '' file; do
  sum=$(zcat -f "$file" | md5sum | cut -d' ' -f1)
  [[ -n ${seen[$sum]:-} ]] && continue
  seen[$sum]=1
  relative=${file#"$root"/}
  example=$(echo "$relative" | awk -F/ '{print (NF >= 4 ? $(NF - 3) : $1)}')
  base=$(basename "$file" .gz)
  target="$work/$example-$base"
  n=2
  while [[ -e $target ]]; do target="$work/$example-$((n++))-$base"; done
  zcat -f "$file" >"$target"
  meshes+=("$target")
done < <(find "$root" -type f \( -iname '*.obj' -o -iname '*.obj.gz' -o -iname '*.stl' -o -iname '*.stl.gz' \) -print0 | sort -z)
echo "openfoam_sweep: ${#meshes[@]} distinct surfaces" >&2
only=$(for m in "${meshes[@]}"; do basename "$m"; done | paste -sd, -)
"$sweep" --only "$only" "$@" "${meshes[@]}"

#!/bin/bash
# Renders every example of Debian's openscad package to binary STL and keeps
# the small ones, unchanged, as the CAD corpus (tests/data/cad, issue 52):
#
#   bash bench/render_cad_corpus.sh build/geodual tests/data/cad [MAX_FACES] [TIMEOUT_S]
#
# Each example is rendered with `openscad --export-format binstl -o NAME.stl
# FILE.scad` (NAME: the file's name without .scad; the examples' names are
# unique), at most TIMEOUT_S seconds each (default 120), from the package's
# own folder so that its imports resolve. A render that fails (a 2D or empty
# top-level object, a timeout) or has more than MAX_FACES faces (default
# 30000) is not kept; OUT_DIR/MANIFEST.tsv lists the kept ones with the
# figures of `geodual info --json` (the reader welds STL corners by exact
# position and nothing else: the render's defects stay), and
# OUT_DIR/NOT_KEPT.tsv the others with why. Needs openscad, python3, sha256sum.
set -euo pipefail

geodual=${1:?usage: render_cad_corpus.sh GEODUAL OUT_DIR [MAX_FACES] [TIMEOUT_S]}
out=${2:?usage: render_cad_corpus.sh GEODUAL OUT_DIR [MAX_FACES] [TIMEOUT_S]}
max_faces=${3:-30000}
timeout_s=${4:-120}
examples=/usr/share/openscad/examples

mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
version=$(openscad --version 2>&1 | sed 's/^OpenSCAD version //')
package=$(dpkg-query -W -f='${Version}' openscad 2>/dev/null || echo unknown)

: >"$work/renders.tsv"
while IFS= read -r scad; do
  name=$(basename "$scad" .scad)
  rc=0
  (cd "$(dirname "$scad")" && timeout "$timeout_s" openscad --export-format binstl -o "$work/$name.stl" "$scad") \
    >"$work/$name.log" 2>&1 || rc=$?
  uses=$(grep -o 'text(\|import(\|surface(' "$scad" | tr -d '(' | sort -u | paste -sd, - || true)
  printf '%s\t%s\t%s\t%s\n' "$name" "$scad" "$rc" "${uses:--}" >>"$work/renders.tsv"
done < <(find "$examples" -name '*.scad' | sort)

: >"$work/info.tsv"
while IFS=$'\t' read -r name scad rc uses; do
  if [ "$rc" = 0 ] && [ -s "$work/$name.stl" ]; then
    "$geodual" info --json "$work/$name.stl" >"$work/$name.json"
  fi
done <"$work/renders.tsv"

python3 - "$work" "$out" "$max_faces" "$timeout_s" "$version" "$package" <<'EOF'
import hashlib, json, math, os, shutil, sys

work, out, max_faces, timeout_s, version, package = sys.argv[1:]
max_faces = int(max_faces)
license_ = ("CC0-1.0 (Debian openscad copyright, Files: examples/*: 2013 Clifford Wolf, Andrew Plumb, "
            "Nathan Hellweg, Emmett Lalish and Marius Kintel)")

def four_digits(x):
    return f"{x:.{max(0, 3 - math.floor(math.log10(abs(x))))}f}" if x else "0"

def last_line(log):
    lines = [l.strip() for l in open(log, errors="replace") if l.strip()]
    return lines[-1] if lines else "no output"

columns = ["file", "source", "openscad_version", "vertices", "faces", "components", "boundary_loops",
           "nonmanifold_edges", "nonmanifold_vertices", "degenerate_faces", "duplicate_vertices",
           "unreferenced_vertices", "duplicate_triangles", "euler_characteristic", "genus", "bbox_diag",
           "welded_corners", "bytes", "uses", "sha256", "license"]
kept, not_kept = [], []
for line in open(os.path.join(work, "renders.tsv")):
    name, scad, rc, uses = line.rstrip("\n").split("\t")
    stl = os.path.join(work, name + ".stl")
    log = os.path.join(work, name + ".log")
    if rc != "0":
        why = f"timed out after {timeout_s} s" if rc == "124" else f"openscad exit {rc}: {last_line(log)}"
        not_kept.append((name, scad, why))
        continue
    if not os.path.exists(stl) or os.path.getsize(stl) <= 84:
        not_kept.append((name, scad, "empty render: " + last_line(log)))
        continue
    info = json.load(open(os.path.join(work, name + ".json")))
    if info["faces"] > max_faces:
        not_kept.append((name, scad, f"{info['faces']} faces, more than {max_faces}"))
        continue
    data = open(stl, "rb").read()
    shutil.copyfile(stl, os.path.join(out, name + ".stl"))
    genus = "*" if info["genus"] is None else (f"{info['genus']:g}")
    kept.append([name + ".stl", scad, f"{version} (Debian {package})", info["vertices"], info["faces"],
                 info["components"], info["boundary_loops"], info["nonmanifold_edges"], info["nonmanifold_vertices"],
                 info["degenerate_faces"], info["duplicate_vertices"], info["unreferenced_vertices"],
                 info["duplicate_faces"], info["euler_characteristic"], genus, four_digits(info["bbox_diagonal"]),
                 info["welded_corners"], len(data), uses, hashlib.sha256(data).hexdigest(), license_])

with open(os.path.join(out, "MANIFEST.tsv"), "w") as f:
    f.write("\t".join(columns) + "\n")
    for row in kept:
        f.write("\t".join(str(c) for c in row) + "\n")
with open(os.path.join(out, "NOT_KEPT.tsv"), "w") as f:
    f.write("name\tsource\twhy\n")
    for row in not_kept:
        f.write("\t".join(row) + "\n")
print(f"kept {len(kept)} renders ({sum(r[17] for r in kept)} bytes), not kept {len(not_kept)}")
EOF

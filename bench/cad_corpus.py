#!/usr/bin/env python3
"""The CAD corpus (tests/data/cad) through geodual's command line, and two such
runs compared: the figures issue notes quote for the corpus.

  bench/cad_corpus.py run BINARY SITES OUT_DIR [PART ...]   # from the repository root
  bench/cad_corpus.py compare DIR_A [DIR_B]

run: `BINARY remesh tests/data/cad/PART.stl --sites SITES --json --samples
100000 -o OUT_DIR/PART.ply`, two parts at a time (every part of the corpus
where none is named); each part's JSON goes to OUT_DIR/PART.json, its stderr
to OUT_DIR/PART.err, and the remesh is deleted.

compare: per part, the long-crease recall (%), H (% of the diagonal), Qmin,
the smallest angle, the vertex count and the time of each run, marked `*`
where the figures differ; then the medians and the number of parts at 99 % or
more. A part whose run failed shows `-`.
"""

import concurrent.futures
import json
import pathlib
import statistics
import subprocess
import sys

CORPUS = pathlib.Path("tests/data/cad")
FIGURES = [  # JSON key, column heading, format
    ("feature_long_recall_pct", "long %", "{:.2f}"),
    ("hausdorff_pct", "H %", "{:.3f}"),
    ("q_min", "Qmin", "{:.3f}"),
    ("theta_min_deg", "θmin", "{:.1f}"),
    ("vertices", "V", "{:d}"),
    ("time_s", "s", "{:.1f}"),
]
COMPARED = FIGURES[:-1]  # the time differs from run to run


def usage():
    sys.exit(__doc__.strip().split("\n\n")[1])


def run(binary, sites, out_dir, parts):
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    parts = parts or sorted(path.stem for path in CORPUS.glob("*.stl"))

    def remesh(part):
        mesh = CORPUS / f"{part}.stl"
        if not mesh.is_file():
            return f"{part}: no {mesh}"
        remeshed = out / f"{part}.ply"
        with open(out / f"{part}.json", "w") as json_file, open(out / f"{part}.err", "w") as err_file:
            status = subprocess.call(
                [binary, "remesh", str(mesh), "--sites", str(sites), "--json", "--samples", "100000", "-o",
                 str(remeshed)], stdout=json_file, stderr=err_file)
        remeshed.unlink(missing_ok=True)
        return f"{part}: exit {status}"

    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for line in pool.map(remesh, parts):
            print(line, flush=True)


def load(directory):
    figures = {}
    for path in sorted(pathlib.Path(directory).glob("*.json")):
        try:
            report = json.loads(path.read_text())
        except ValueError:
            report = None
        figures[path.stem] = report
    return figures


def cell(report, key, fmt):
    value = report.get(key) if report else None
    return "-" if value is None else fmt.format(value)


def compare(directories):
    runs = [load(directory) for directory in directories]
    parts = sorted(set().union(*runs))
    heading = ["part"] + [f"{title} {chr(ord('A') + i)}" for _, title, _ in FIGURES for i in range(len(runs))]
    print(" | ".join(heading))
    for part in parts:
        reports = [figures.get(part) for figures in runs]
        cells = [cell(report, key, fmt) for key, _, fmt in FIGURES for report in reports]
        differs = any(len({cell(report, key, fmt) for report in reports}) > 1 for key, _, fmt in COMPARED)
        print(" | ".join([part] + cells) + (" *" if differs else ""))
    for i, figures in enumerate(runs):
        reports = [report for report in figures.values() if report]
        medians = []
        for key, title, fmt in COMPARED:
            values = [report[key] for report in reports if report.get(key) is not None]
            medians.append(f"{title} {statistics.median(values):.4g}" if values else f"{title} -")
        long_kept = sum(1 for report in reports if (report.get("feature_long_recall_pct") or 0) >= 99)
        print(f"{chr(ord('A') + i)} ({directories[i]}): {len(reports)} parts; medians: " + ", ".join(medians) +
              f"; long-crease recall >= 99 %: {long_kept} parts")


def main(arguments):
    if len(arguments) >= 4 and arguments[0] == "run":
        run(arguments[1], int(arguments[2]), arguments[3], arguments[4:])
    elif 2 <= len(arguments) <= 3 and arguments[0] == "compare":
        compare(arguments[1:])
    else:
        usage()


if __name__ == "__main__":
    main(sys.argv[1:])

#!/usr/bin/env python3
"""Print doc/results.md from the output directory of the main job.

    bash scripts/run-main-job.sh                      # writes results/
    python3 scripts/make-results-doc.py results > doc/results.md

scripts/main-job.sh runs this at its end and writes DIR/results.md; it never
overwrites doc/results.md.

Each table is headed by one line "measured at <commit>, <date>, <machine>" and the
command that makes its input file. The commit is `git rev-parse --short HEAD`, the date
that of the input file (UTC), the machine the operating system, `uname -m` and the
number of cores. A file FILE.measured-at next to an input overrides that line (for an
input made at another time or on another machine).

The main job makes the comparison tables (comparison-*.md) and the refinement
records (refine-*.csv, refine-*.txt). The other inputs are made by the commands the
document prints where they are missing (the speed ratios, Table 4.1, 512^3, the
calculators, the distances to the marching-cubes surface).

Python 3 standard library only.
"""

import argparse
import csv
import datetime
import json
import os
import platform
import re
import subprocess
import sys

ME = "build/examples/meshextraction"
COMPARE = "build/examples/meshextraction-compare"
BENCHMARKS = "build/benchmark/MeshExtractionBenchmarks"
NOT_RECORDED = "n/r"

PHANTOM_COLUMNS = ["method", "triangles", "q_angle", "q_area", "<0.3 %", "vert mean", "vert max", "face mean",
                   "valid", "time s"]
IMAGE_COLUMNS = ["method", "triangles", "q_angle", "q_area", "<0.3 %", "valid", "bnd-edges", "self-x", "time s"]
LARGE_COLUMNS = ["method", "triangles", "q_angle", "q_area", "vert mean", "time s", "peak MiB"]

# meshextraction-compare's method keys (the mesh files of --write-meshes) and row names.
METHOD_NAMES = {
    "mc": "vtkMarchingCubes",
    "fe": "vtkFlyingEdges3D",
    "fe-sinc": "FlyingEdges3D+WindowedSinc",
    "bmms": "itkBinaryMask3DMeshSource",
    "sna": "SurfaceNets SNA",
    "snert": "SurfaceNets SNERT",
    "slicer": "Slicer labelmap DFE+Sinc0.01",
    "sn-hq": "SurfaceNets HQ",
    "sn-hq-iso": "SurfaceNets HQ isotropic",
    "sn-hq-remesh": "SurfaceNets HQ remeshed",
}

# Thesis Table 4.1 (noiseless sphere): q_area, mean radius, variance per step.
THESIS_TABLE_41 = {
    ("Org", True): "0.76, 24.78, 0.471",
    ("ED", True): "0.75, 25.01, 0.038",
    ("ES", True): "0.77",
    ("S", True): "0.89–0.93, 24.82–23.76",
    ("S", False): "0.89–0.93, 24.82–23.76",
    ("ED", False): "0.91–0.93, 24.98–24.92, 0.044–0.049",
    ("ES", False): "0.91–0.93",
}

PREAMBLE = """\
Results
=======

Made by `python3 scripts/make-results-doc.py {dir} > doc/results.md` after
`bash scripts/run-main-job.sh` (the main job also writes it as `{dir}/results.md`).
Every table says where and when it was measured, and which command makes its input.
Times are wall clock on the machine named; on a shared 2-core virtual machine they vary
by up to 30 % between runs, so compare only times measured together. How the figures
changed over time is in doc/history.md.

Measures (thesis section 4.2.3): q_area = 4√3·A/Σe² and q_angle = smallest/largest angle
are 1 for an equilateral triangle; "<0.3 %" is the share of triangles with q_angle below
0.3. "valid" means a closed, 2-manifold, outward-oriented surface without degenerate,
inverted or self-intersecting triangles; "bnd-edges" counts boundary edges (holes),
"self-x" pairs of triangles that intersect. Distances are in mm.
"""


def git_commit():
    try:
        out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], check=True, stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, universal_newlines=True,
                             cwd=os.path.dirname(os.path.abspath(__file__)))
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown commit"


def machine():
    system = platform.system()
    try:
        with open("/etc/os-release") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    system = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    return "{}, {}, {} cores".format(system, platform.machine(), os.cpu_count())


class Context:
    def __init__(self, directory):
        self.directory = directory
        self.commit = git_commit()
        self.machine = machine()

    def path(self, name):
        return os.path.join(self.directory, name)

    def exists(self, name):
        return os.path.isfile(self.path(name))

    def measured_at(self, name):
        """The header line of a table made from input file `name`."""
        override = self.path(name) + ".measured-at"
        if os.path.isfile(override):
            with open(override) as f:
                return "measured at " + f.read().strip()
        date = datetime.datetime.fromtimestamp(os.path.getmtime(self.path(name)), datetime.timezone.utc)
        return "measured at {}, {}, {}".format(self.commit, date.strftime("%Y-%m-%d"), self.machine)


def heading(title, ctx, name, command):
    """The section title, the measured-at line and the command; False if `name` is missing."""
    print("\n### " + title + "\n")
    if not ctx.exists(name):
        print("Not in this results directory ({}). Make it with:\n\n```sh\n{}\n```".format(
            ctx.path(name), command))
        return False
    print(ctx.measured_at(name) + "  ")
    print("`" + command + "`\n")
    return True


def markdown_table(header, rows, right=None):
    """A Markdown table; `right`: which columns are right-aligned (default all but the first)."""
    right = right if right is not None else [i > 0 for i in range(len(header))]
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---:" if r else "---" for r in right) + "|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


def read_comparison(path):
    """The table of a meshextraction-compare --markdown file: (header, rows)."""
    header, rows = None, []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line.startswith("|"):
                if header is not None and rows:
                    break
                continue
            cells = [c.strip() for c in line.strip("|").split("|")]
            if header is None:
                header = cells
            elif all(re.fullmatch(r":?-+:?", c) for c in cells):
                continue
            else:
                rows.append(cells + [""] * (len(header) - len(cells)))
    if header is None:
        sys.exit("{}: no table".format(path))
    return header, rows


def comparison(ctx, title, name, command, columns, caption):
    if not heading(title, ctx, name, command):
        return
    header, rows = read_comparison(ctx.path(name))
    missing = [c for c in columns if c not in header]
    if missing:
        sys.exit("{}: no column {}".format(ctx.path(name), ", ".join(missing)))
    index = [header.index(c) for c in columns]
    if caption:
        print(caption + "\n")
    markdown_table(columns, [[row[i] for i in index] for row in rows])


def mc_distances(ctx):
    name = "cranium-distances.json"
    keys = ["sn-hq", "sn-hq-iso", "snert", "fe-sinc", "slicer"]
    meshes = " ".join("{}/cranium-methods/{}.vtk".format(ctx.directory, k) for k in keys)
    command = "{} quality {} --reference-mesh {}/cranium-methods/mc.vtk --json {}/{}".format(
        ME, meshes, ctx.directory, ctx.directory, name)
    if not heading("Head CT: distances to the marching-cubes surface", ctx, name, command):
        return
    with open(ctx.path(name)) as f:
        entries = json.load(f)
    print("Mean distance of the vertices and of the face centroids to the vtkMarchingCubes surface "
          "(the meshes of `meshextraction-compare --write-meshes`).\n")
    rows = []
    for entry in entries:
        key = os.path.splitext(os.path.basename(entry["mesh"]))[0]
        distance = entry.get("distance", {})
        cells = []
        for part in ("vertices", "face_centroids"):
            value = distance.get(part, {}).get("mean")
            cells.append(NOT_RECORDED if value is None else "{:.3f}".format(value))
        rows.append([METHOD_NAMES.get(key, key)] + cells)
    markdown_table(["method", "vert mean", "face mean"], rows)


# PrintScaleSpaceRefinementTable's columns (itkMeshExtractionScaleSpaceRefinementSteps.cxx).
STEP_WIDTHS = [5, 6, 10, 9, 11, 12, 10, 9, 9, 8, 8, 7, 7, 7, 9]
STEP_FIELDS = ["op", "cycle", "min_angle", "q_area", "inaccuracy", "distance", "variance", "changes", "rejected",
               "mean_move", "max_move", "degenerate", "non_manifold", "inverted", "seconds"]


def parse_step_row(line):
    row, start = {}, 0
    for width, field in zip(STEP_WIDTHS, STEP_FIELDS):
        row[field] = line[start:start + width].strip()
        start += width
    return row


def read_protocols(path):
    """{noise: [step rows]} from the output of the Table41 tests."""
    protocols, current = {}, None
    with open(path) as f:
        for line in f:
            match = re.match(r"Protocol on the chapter-4 sphere, noise ([0-9.]+):", line)
            if match:
                current = protocols.setdefault(match.group(1), [])
                continue
            if current is not None:
                if line.startswith("Op "):
                    continue
                if re.match(r"(Org|ED|ES|S) ", line):
                    current.append(parse_step_row(line.rstrip("\n")))
                else:
                    current = None
    return protocols


def table41(ctx):
    name = "table41.txt"
    command = ("build/test/MeshExtractionGTestDriver --gtest_filter='ScaleSpaceEdgeMeshRefinementFilter.Table41*' "
               "> {}/{}".format(ctx.directory, name))
    if not heading("Scale-space edge refinement: thesis Table 4.1", ctx, name, command):
        return
    protocols = read_protocols(ctx.path(name))
    if not protocols:
        sys.exit("{}: no protocol table".format(ctx.path(name)))
    print("A 100³ sphere of radius 25 (chapter-4 phantom); the start is a perturbed 642-vertex geodesic "
          "sphere with the thesis' mean radius 24.78 and variance 0.471. Maximum deviation 3 mm, target "
          "quality 0.9.\n")
    noiseless = protocols.get("0") or protocols[sorted(protocols)[0]]
    seen, rows = set(), []
    for step in noiseless:
        first = step["op"] not in seen
        seen.add(step["op"])
        rows.append([step["op"], step["min_angle"], step["q_area"], step["inaccuracy"], step["distance"],
                     step["variance"], THESIS_TABLE_41.get((step["op"], first), "")])
    markdown_table(["step", "min. angle", "q_area", "inaccuracy", "mean radius", "variance",
                    "thesis: q_area, radius, variance"], rows, [False] + [True] * 5 + [False])
    deviation = 0.0
    for noise in sorted(protocols, key=float):
        steps = protocols[noise]
        detections = [s for s in steps if s["op"] == "ED"]
        for s in detections:
            deviation = max(deviation, abs(float(s["distance"]) - 25.0))
        if float(noise) == 0.0:
            continue
        print("\nWith Gaussian noise σ = {}: ED mean radius {}, variance {}, final q_area {}.".format(
            noise, " and ".join(s["distance"] for s in detections), " and ".join(s["variance"] for s in detections),
            steps[-1]["q_area"]))
    print("\nEvery ED leaves the mean radius within {:.3f} of 25 (thesis: 0.25).".format(deviation))


def read_refinement_report(path):
    """(initial, final) rows of the quality comparison and the summary line of `refine --report`."""
    rows, summary = [], ""
    with open(path) as f:
        lines = f.read().splitlines()
    in_table = False
    for line in lines:
        if re.match(r"\d+ cycles, target quality", line):
            summary = line
        if line.startswith("mesh") and "triangles" in line and "q_area" in line:
            in_table, rows = True, []
            continue
        if in_table:
            tokens = line.split()
            if len(tokens) < 11:
                in_table = False
                continue
            rows.append({"triangles": tokens[-10], "q_area": tokens[-9], "q_angle": tokens[-8],
                         "below03": tokens[-7], "valid": tokens[-1].lower()})
    return rows, summary


def value_range(values, digits):
    if not values:
        return NOT_RECORDED
    low, high = min(values), max(values)
    if round(low, digits) == round(high, digits):
        return "{:.{}f}".format(low, digits)
    return "{:.{}f}–{:.{}f}".format(low, digits, high, digits)


def refinement(ctx, title, stem, command, target, caption):
    csv_name, report_name = "refine-{}.csv".format(stem), "refine-{}.txt".format(stem)
    if not heading(title, ctx, csv_name, command):
        return
    with open(ctx.path(csv_name)) as f:
        steps = list(csv.DictReader(f))
    report, summary = ([], "")
    if ctx.exists(report_name):
        report, summary = read_refinement_report(ctx.path(report_name))
    if caption:
        print(caption + "\n")

    def number(step, field):
        return float(step[field]) if step.get(field) not in (None, "") else None

    start = report[0] if len(report) == 2 else {}
    end = report[1] if len(report) == 2 else {}
    first, last = steps[0], steps[-1]
    rows = [
        ["triangles", start.get("triangles", first["triangles"]), end.get("triangles", last["triangles"])],
        ["mean q_area", start.get("q_area", "{:.4f}".format(float(first["mean_q_area"]))),
         end.get("q_area", "{:.4f}".format(float(last["mean_q_area"])))],
        ["mean q_angle", start.get("q_angle", NOT_RECORDED), end.get("q_angle", NOT_RECORDED)],
        ["q_angle < 0.3 (%)", start.get("below03", NOT_RECORDED), end.get("below03", NOT_RECORDED)],
        ["valid", start.get("valid", NOT_RECORDED), end.get("valid", NOT_RECORDED)],
    ]
    markdown_table(["", "start", "end"], rows)
    detections = [s for s in steps if s["operation"] == "ED"]
    swaps = [s for s in steps if s["operation"] == "ES"]
    inaccuracy = [number(s, "inaccuracy_mm") for s in detections if number(s, "inaccuracy_mm") is not None]
    moves = [number(s, "mean_travel_mm") for s in detections if number(s, "mean_travel_mm") is not None]
    qualities = [number(s, "mean_q_area") for s in steps if number(s, "mean_q_area") is not None]
    reached = "not recorded"
    if summary:
        reached = "not reached" if "NOT reached" in summary else "reached"
    total = re.search(r"([0-9.]+) s in all", summary)
    ed_seconds = [number(s, "seconds") for s in detections if number(s, "seconds") is not None]
    es_seconds = [number(s, "seconds") for s in swaps if number(s, "seconds") is not None]
    print("\n- ED steps: {}; inaccuracy (mean distance of the triangles to the detected edge) {} mm after the "
          "first, {} mm after the last; mean ED move {} → {} mm.".format(
              len(detections), "{:.3f}".format(inaccuracy[0]) if inaccuracy else NOT_RECORDED,
              "{:.3f}".format(inaccuracy[-1]) if inaccuracy else NOT_RECORDED,
              "{:.2f}".format(moves[0]) if moves else NOT_RECORDED,
              "{:.2f}".format(moves[-1]) if moves else NOT_RECORDED))
    print("- Highest mean q_area on the way: {}; target {}: {}.".format(
        "{:.3f}".format(max(qualities)) if qualities else NOT_RECORDED, target, reached))
    print("- Time: {} s in all; ED {} s the first (with the scale space), then {} s; ES {} s.".format(
        "{:.1f}".format(float(total.group(1))) if total else NOT_RECORDED,
        "{:.1f}".format(ed_seconds[0]) if ed_seconds else NOT_RECORDED, value_range(ed_seconds[1:], 1),
        value_range(es_seconds, 1)))


def read_ratios(path):
    """The last round's wall-time table and the summary over the rounds (or the ratio table
    of a single round) from the output of benchmark/ratios.py."""
    with open(path) as f:
        lines = f.read().splitlines()

    def block(start):
        out = []
        for line in lines[start:]:
            if not line.strip():
                break
            out.append(line)
        return out

    rounds = [i for i, line in enumerate(lines) if re.match(r"round \d+: ", line) and ": baseline " not in line]
    walls = [i for i, line in enumerate(lines) if line.startswith("wall time per extraction")]
    summaries = [i for i, line in enumerate(lines) if re.match(r"over \d+ rounds", line)]
    ratio_tables = [i for i, line in enumerate(lines) if line.startswith("ratios (")]
    if not walls:
        sys.exit("{}: no wall-time table".format(path))
    wall = block(walls[-1])
    total = len(rounds)
    if summaries:
        total = int(re.match(r"over (\d+) rounds", lines[summaries[-1]]).group(1))
    if total > 1:
        before = [i for i in rounds if i < walls[-1]]
        number = int(re.match(r"round (\d+)", lines[before[-1]]).group(1)) if before else total
        wall[0] = "wall time per extraction (ms), round {} of {}".format(number, total)
    else:
        wall[0] = "wall time per extraction (ms)"
    second = block(summaries[-1]) if summaries else (block(ratio_tables[-1]) if ratio_tables else [])
    return wall, second


def speed(ctx):
    name = "ratios.txt"
    command = "python3 benchmark/ratios.py {} --repetitions 3 --rounds 2 > {}/{}".format(
        BENCHMARKS, ctx.directory, name)
    if not heading("Speed against VTK", ctx, name, command):
        return
    wall, summary = read_ratios(ctx.path(name))
    print("Google Benchmark, each method in a process of its own, best of the repetitions; sphere distance "
          "map, float, 1 mm voxels. \"net core\": the net into flat arrays; \"net\": the filter to an "
          "`itk::Mesh` without relaxation; HQ: the high-quality mode; FE3D: vtkFlyingEdges3D; FE+sinc: "
          "FE3D + windowed sinc (3D Slicer's smoothing). \"1 thread\" is `SetNumberOfWorkUnits(1)` and "
          "VTK's SMP backend limited to 1. Targets: core/FE3D ≤ 1, SNERT/(FE+sinc) ≤ 2, HQ/FE3D ≤ 10. "
          "At 128³ FlyingEdges3D's time is mostly first-touched memory, so only the 256³ ratios "
          "compare the methods (see benchmark/README.md).\n")
    print("```")
    print("\n".join(wall))
    if summary:
        print("")
        print("\n".join(summary))
    print("```")


def large(ctx):
    name = "comparison-sphere-512.md"
    command = ("{} --phantom sphere --size 512 --methods fe,fe-sinc,snert,sn-hq --repeat 1 --markdown {}/{}"
               .format(COMPARE, ctx.directory, name))
    caption = ("All cores; each method in a forked child process, so with fresh memory; the float input "
               "(512 MiB) is not counted in \"peak MiB\". Distances to the exact sphere.")
    comparison(ctx, "Sphere distance map at 512³", name, command, LARGE_COLUMNS, caption)


def calculators(ctx):
    name = "calculators.json"
    command = ("{} --benchmark_filter='Triangle|Distance' --benchmark_repetitions=3 --benchmark_format=json "
               "> {}/{}".format(BENCHMARKS, ctx.directory, name))
    if not heading("The quality and distance calculators", ctx, name, command):
        return
    with open(ctx.path(name)) as f:
        results = json.load(f)
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    times = {}
    for entry in results.get("benchmarks", []):
        if entry.get("run_type", "iteration") != "iteration" or entry.get("error_occurred"):
            continue
        base = re.sub(r"/real_time$", "", entry.get("run_name", entry["name"]))
        times.setdefault(base, []).append(entry["real_time"] * unit[entry.get("time_unit", "ns")])
    what = [
        ("TriangleMeshQualityCalculator/1M", "all measures of a 1,000,000-triangle torus"),
        ("TriangleMeshQualityCalculator/1M/NoSelfIntersections", "the same without the self-intersection test"),
        ("MeshSurfaceDistanceCalculator/1Mpoints/1Mtriangles",
         "distances of 998,784 points (vertices and face centroids) to a 1,000,000-triangle mesh"),
    ]
    print("Wall time of one computation, fastest to slowest repetition.\n")
    markdown_table(["benchmark", "what", "time s"],
                   [[b, w, value_range(times.get(b, []), 2)] for b, w in what], [False, False, True])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", nargs="?", default="results", help="the main job's output directory")
    args = parser.parse_args()
    if not os.path.isdir(args.directory):
        sys.exit("{}: not a directory (run bash scripts/run-main-job.sh first)".format(args.directory))
    ctx = Context(args.directory.rstrip("/") or args.directory)
    d = ctx.directory
    print(PREAMBLE.format(dir=d), end="")

    print("\nExtraction\n----------")
    phantom_caption = ("All cores; time: best of 3 runs, each method in a forked child process; distances "
                       "to the exact surface.")
    comparison(ctx, "Sphere distance map, 128³ (radius 38.4 mm)", "comparison-sphere.md",
               "{} --phantom sphere --size 128 --methods all --markdown {}/comparison-sphere.md".format(COMPARE, d),
               PHANTOM_COLUMNS, phantom_caption)
    comparison(ctx, "Two overlapping spheres, 128³ (a crease where they meet)", "comparison-two-spheres.md",
               "{} --phantom two-spheres --size 128 --methods all --markdown {}/comparison-two-spheres.md".format(
                   COMPARE, d), PHANTOM_COLUMNS, phantom_caption)
    comparison(ctx, "Head CT, bone at 300 HU", "comparison-cranium.md",
               "{} {}/data/cranium.nhdr --iso 300 --methods all --repeat 1 --write-meshes {}/cranium-methods "
               "--markdown {}/comparison-cranium.md".format(COMPARE, d, d, d), IMAGE_COLUMNS,
               "Debian's invesalius-examples Cranium (256×256×108, 0.957×0.957×1.5 mm; `scripts/prepare-data.sh`). "
               "No exact surface, so no distances. The skull touches the image border. "
               "All cores; time of one run.")
    mc_distances(ctx)
    comparison(ctx, "Small head CT (headsq), bone at 1150", "comparison-headsq.md",
               "{} {}/data/headsq.nhdr --iso 1150 --methods all --repeat 1 --markdown {}/comparison-headsq.md".format(
                   COMPARE, d, d), IMAGE_COLUMNS,
               "VTK's ct_headsq (64×64×93, 3.2×3.2×1.5 mm; HU + 1024), when `../shared/data/ct_headsq` is "
               "present. All cores; time of one run.")

    print("\nRefinement (thesis chapter 4)\n-----------------------------")
    table41(ctx)
    refinement(ctx, "Brain surface of the Colin27 T1 MRI", "brain",
               "{} refine /usr/share/mricron/templates/ch2.nii.gz {}/brain-rough.vtk {}/brain-refined.vtk "
               "--largest-component --max-deviation 1.5 --target-quality 0.9 --csv {}/refine-brain.csv --report "
               "> {}/refine-brain.txt".format(ME, d, d, d, d), 0.9,
               "Debian's mricron-data (181×217×181, 1 mm). The start is a SurfaceNets SNA mesh of the "
               "brain-extracted image (ch2bet, `extract ... --iso 1 --relaxation sna`), its largest component; "
               "it is refined against the T1 itself.")
    refinement(ctx, "Bone surface of the head CT", "cranium",
               "{} refine {}/data/cranium.nhdr {}/cranium-refined.vtk --initial surfacenets --iso 300 "
               "--max-deviation 2 --target-quality 0.9 --csv {}/refine-cranium.csv --report "
               "> {}/refine-cranium.txt".format(ME, d, d, d, d), 0.9,
               "The start is the unrelaxed SurfaceNets mesh at 300 HU (229 components).")

    print("\nConnected orthogonal contours (thesis chapter 5)\n------------------------------------------------")
    contours = "contours-study.md"
    if ctx.exists(contours):
        header, _ = read_comparison(ctx.path(contours))
        comparison(ctx, "Simulated user: the analogue of Table 5.1", contours,
                   "build/examples/meshextraction-contours-study --markdown {}/contours-study.md".format(d), header,
                   "From the three-contour template until the mean contour error is at most 0.5 voxel (12 contours "
                   "at most for the phantoms, 15 for the ventricle); errors in voxels (1 mm), mean / max. The "
                   "ventricle's reference: the Colin27 T1's voxels below 40, the largest component inside the head, "
                   "meshed by SurfaceNets in the high-quality mode.")
    else:
        heading("Simulated user: the analogue of Table 5.1", ctx, contours,
                "build/examples/meshextraction-contours-study --markdown {}/contours-study.md".format(d))

    print("\nSpeed\n-----")
    speed(ctx)
    large(ctx)
    calculators(ctx)


if __name__ == "__main__":
    main()

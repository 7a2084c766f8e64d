#!/usr/bin/env python3
"""The command-line tool's figures on the sphere phantom, which the Python tests must
match (test_surface_nets.py): the same image and settings give the same triangles and
q_area from the wrapped filter as from `meshextraction extract`.

  cli_reference.py --cli build/examples/meshextraction --check   (a CTest test)
  cli_reference.py --cli build/examples/meshextraction --write   (after a deliberate change)

--check fails when the tool's figures have moved from cli_sphere_reference.json, so the
file the Python tests read stays the tool's."""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "cli_sphere_reference.json")
SIZE = 64
# Each method: the options of `extract`; the Python tests set the same on the filter.
METHODS = {
    "sna": ["--relaxation", "sna"],
    "snert": ["--relaxation", "snert"],
    "high": ["--quality", "high"],
    "high-remeshing": ["--quality", "high", "--remeshing", "on"],
}


def measure(cli, options, directory):
    report = os.path.join(directory, "report.json")
    command = [cli, "extract", "--phantom", "sphere", "--size", str(SIZE), os.path.join(directory, "out.vtk"),
               *options, "--report-json", report]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("%s failed (%d):\n%s" % (" ".join(command), run.returncode, run.stderr))
    with open(report, encoding="utf-8") as f:
        measured = json.load(f)[0]
    return {"triangles": measured["quality"]["triangles"], "q_area": measured["quality"]["q_area"]["mean"],
            "vertex_mean_distance": measured["distance"]["vertices"]["mean"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cli", required=True, help="the meshextraction executable")
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--check", action="store_true", help="compare with the reference file")
    action.add_argument("--write", action="store_true", help="write the reference file")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        figures = {name: dict(options=options, **measure(args.cli, options, directory))
                   for name, options in METHODS.items()}
    if args.write:
        with open(REFERENCE, "w", encoding="utf-8") as f:
            json.dump({"phantom": "sphere", "size": SIZE, "methods": figures}, f, indent=2)
            f.write("\n")
        print("wrote", REFERENCE)
        return 0
    with open(REFERENCE, encoding="utf-8") as f:
        reference = json.load(f)["methods"]
    problems = []
    for name, measured in figures.items():
        expected = reference.get(name)
        if expected is None or expected["triangles"] != measured["triangles"] or not math.isclose(
                expected["q_area"], measured["q_area"], abs_tol=1e-6):
            problems.append("%s: the tool gives %s, the reference %s" % (name, measured, expected))
    for problem in problems:
        print(problem, file=sys.stderr)
    print("cli reference: %d of %d methods as recorded" % (len(figures) - len(problems), len(figures)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Run MeshExtractionBenchmarks and print the speed ratios issues 5 and 6 ask for.

    python3 benchmark/ratios.py BUILD/benchmark/MeshExtractionBenchmarks [--large]
    python3 benchmark/ratios.py BINARY --repetitions 3     (best of 3, on a busy machine)
    python3 benchmark/ratios.py --json results.json       (ratios of an earlier run)
    python3 benchmark/ratios.py BINARY --rounds 3         (three runs in a row, and the range
                                                           of each ratio over them)
    python3 benchmark/ratios.py BINARY --rounds 3 --baseline OLD_BINARY
                                                          (each round runs OLD, then BINARY:
                                                           paired times new/old per method)

Each method runs in a process of its own (--one-process: all in one).

For every size and thread count (1 and all):
  net construction / vtkFlyingEdges3D           issue 5 target: <= 1
      ("net core": classification, net and faces into flat arrays, as FlyingEdges
       makes them; "net": the filter to an itk::Mesh, one TriangleCell per face, in one block)
  SNA / vtkFlyingEdges3D
  SNERT / (FlyingEdges3D + windowed sinc)       issue 5 target: <= 2
  HQ / vtkFlyingEdges3D                          issue 6 target: <= 10
  HQ / SNERT, HQ / (FlyingEdges3D + windowed sinc)
Times are wall-clock (the extraction benchmarks time each run by hand: UseManualTime).
A second table gives each method's minor page faults per run (the benchmark's counter
`faults`): fresh memory from the system, whose cost on a VM can outweigh the computing
and which depends on what the process freed before. Python standard library only.
"""

import argparse
import json
import re
import subprocess
import sys

NAME = re.compile(r"^(?P<method>.+?)/size:(?P<size>\d+)/threads:(?P<threads>\d+)")
UNIT = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}

COLUMNS = [  # (benchmark name, short label)
    ("SurfaceNets/NetConstruction", "net core"),
    ("SurfaceNets/NoRelaxation", "net"),
    ("SurfaceNets/SNA", "SNA"),
    ("SurfaceNets/SNERT", "SNERT"),
    ("SurfaceNets/HQ", "HQ"),
    ("VTK/FlyingEdges3D", "FE3D"),
    ("VTK/FlyingEdges3D+WindowedSinc", "FE+sinc"),
]

RATIOS = [  # (label, numerator, denominator, target)
    ("core/FE3D", "net core", "FE3D", 1.0),
    ("net/FE3D", "net", "FE3D", 1.0),
    ("SNA/FE3D", "SNA", "FE3D", None),
    ("SNERT/(FE+sinc)", "SNERT", "FE+sinc", 2.0),
    ("HQ/FE3D", "HQ", "FE3D", 10.0),
    ("HQ/SNERT", "HQ", "SNERT", None),
    ("HQ/(FE+sinc)", "HQ", "FE+sinc", None),
]


def run_benchmarks(binary, large, repetitions, extra, one_process=False):
    """Run the extraction benchmarks, each method in a process of its own unless
    one_process: in one process, what one method leaves on the heap changes the
    page faults and allocation times of the next, by more than the differences
    measured here."""
    filters = ["^(SurfaceNets|VTK)/"] if one_process else \
        ["^" + re.escape(name) + "/" for name, _ in COLUMNS]
    merged = None
    for benchmark_filter in filters:
        command = [binary, "--benchmark_format=json", "--benchmark_filter=" + benchmark_filter]
        if large:
            command.append("--large")
        if repetitions > 1:
            command.append("--benchmark_repetitions={}".format(repetitions))
        command += extra
        print("running:", " ".join(command), file=sys.stderr)
        result = subprocess.run(command, check=True, stdout=subprocess.PIPE, universal_newlines=True)
        output = json.loads(result.stdout)
        if merged is None:
            merged = output
        else:
            merged["benchmarks"] += output.get("benchmarks", [])
    return merged


def collect(results, counter=None):
    """{(size, threads): {label: milliseconds}} from Google Benchmark's JSON (with
    counter: that counter's value in the fastest repetition instead)."""
    label_of = dict(COLUMNS)
    times = {}
    best = {}
    for entry in results.get("benchmarks", []):
        if entry.get("run_type") == "aggregate" and entry.get("aggregate_name") != "median":
            continue
        if "error_occurred" in entry and entry["error_occurred"]:
            continue
        match = NAME.match(entry.get("run_name", entry["name"]))
        if not match or match.group("method") not in label_of:
            continue
        key = (int(match.group("size")), int(match.group("threads")))
        label = label_of[match.group("method")]
        ms = entry["real_time"] * UNIT[entry.get("time_unit", "ns")]
        cell = times.setdefault(key, {})
        if label in cell and best[(key, label)] <= ms:
            continue  # repetitions: the best one
        best[(key, label)] = ms
        if counter is None:
            cell[label] = ms
        elif counter in entry:
            cell[label] = entry[counter]
    return times


def print_method_table(title, values, number_format):
    """One row per (size, threads), one column per method."""
    labels = [label for _, label in COLUMNS]
    print("\n" + title)
    print("{:>6} {:>7} ".format("size", "threads") + " ".join("{:>9}".format(l) for l in labels))
    for (size, threads) in sorted(values):
        row = values[(size, threads)]
        print("{:>5}^3 {:>7} ".format(size, threads) +
              " ".join("{:>9}".format(number_format.format(row[l]) if l in row else "-") for l in labels))


def print_tables(times, context, faults=None):
    if context:
        print("machine: {} x {} MHz, load average {}; date {}".format(
            context.get("num_cpus"), context.get("mhz_per_cpu"),
            ", ".join("{:.2f}".format(x) for x in context.get("load_avg", [])), context.get("date")))
    print_method_table("wall time per extraction (ms), sphere distance map, float, 1 mm voxels", times, "{:.1f}")
    if faults:
        print_method_table("minor page faults per extraction (fresh pages, 4 KiB or huge; the fastest repetition's mean)",
                           faults, "{:.0f}")

    print("\nratios (SurfaceNets time / peer time; lower is faster)")
    print("{:>6} {:>7} ".format("size", "threads") +
          " ".join("{:>16}".format(label) for label, _, _, _ in RATIOS))
    print("{:>6} {:>7} ".format("", "target") +
          " ".join("{:>16}".format("<= {:g}".format(t) if t else "") for _, _, _, t in RATIOS))
    for (size, threads) in sorted(times):
        row = times[(size, threads)]
        cells = []
        for _, numerator, denominator, target in RATIOS:
            if numerator in row and denominator in row and row[denominator] > 0:
                ratio = row[numerator] / row[denominator]
                mark = "" if target is None else (" ok" if ratio <= target else " NO")
                cells.append("{:.2f}{}".format(ratio, mark))
            else:
                cells.append("-")
        print("{:>5}^3 {:>7} ".format(size, threads) + " ".join("{:>16}".format(c) for c in cells))


def ratio_cells(row):
    """{label: ratio} of one (size, threads) row."""
    cells = {}
    for label, numerator, denominator, _ in RATIOS:
        if numerator in row and denominator in row and row[denominator] > 0:
            cells[label] = row[numerator] / row[denominator]
    return cells


def print_summary(rounds):
    """The range of each ratio with a target over the rounds, and how many met it."""
    print("\nover {} rounds: range of each ratio (rounds that met the target)".format(len(rounds)))
    targeted = [(label, target) for label, _, _, target in RATIOS if target is not None]
    print("{:>6} {:>7} ".format("size", "threads") + " ".join("{:>22}".format(l) for l, _ in targeted))
    for key in sorted(rounds[0]):
        values = [ratio_cells(times.get(key, {})) for times in rounds]
        cells = []
        for label, target in targeted:
            seen = [v[label] for v in values if label in v]
            if not seen:
                cells.append("-")
                continue
            met = sum(1 for x in seen if x <= target)
            cells.append("{:.2f}-{:.2f} ({}/{})".format(min(seen), max(seen), met, len(seen)))
        print("{:>5}^3 {:>7} ".format(*key) + " ".join("{:>22}".format(c) for c in cells))


def print_paired(pairs):
    """Per method: this build's time / the baseline's, in each round (run one after the other)."""
    labels = [label for _, label in COLUMNS]
    print("\npaired with the baseline, one after the other: time / baseline time per round")
    print("{:>6} {:>7} ".format("size", "threads") + " ".join("{:>16}".format(l) for l in labels))
    for key in sorted(pairs[0][1]):
        cells = []
        for label in labels:
            r = ["{:.2f}".format(new[key][label] / old[key][label]) for old, new in pairs
                 if key in old and key in new and label in old[key] and label in new[key] and old[key][label] > 0]
            cells.append(" ".join(r) if r else "-")
        print("{:>5}^3 {:>7} ".format(*key) + " ".join("{:>16}".format(c) for c in cells))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binary", nargs="?", help="the MeshExtractionBenchmarks executable")
    parser.add_argument("--large", action="store_true", help="include the 512^3 cases")
    parser.add_argument("--repetitions", type=int, default=1,
                        help="repeat every benchmark N times and keep the best (for a shared, noisy machine)")
    parser.add_argument("--one-process", action="store_true",
                        help="run all benchmarks in one process (by default each method gets its own)")
    parser.add_argument("--json", help="read the results of an earlier --benchmark_format=json run instead")
    parser.add_argument("--save", help="write the benchmark's JSON output to this file")
    parser.add_argument("--rounds", type=int, default=1,
                        help="run everything N times in a row and summarise the ratios' ranges")
    parser.add_argument("--baseline", help="another MeshExtractionBenchmarks, run before this one in every round")
    parser.add_argument("extra", nargs="*", help="further arguments for the benchmark (after --)")
    args = parser.parse_args()
    if args.binary and not args.json and (args.rounds > 1 or args.baseline):
        if args.save:
            parser.error("--save writes the JSON of a single run: not with --rounds or --baseline")
        rounds = []
        pairs = []
        for r in range(args.rounds):
            old = None
            if args.baseline:
                print("round {}: baseline {}".format(r + 1, args.baseline))
                old = collect(run_benchmarks(args.baseline, args.large, args.repetitions, args.extra,
                                             args.one_process))
            results = run_benchmarks(args.binary, args.large, args.repetitions, args.extra, args.one_process)
            times = collect(results)
            if not times:
                sys.exit("no SurfaceNets/VTK extraction results found")
            print("round {}: {}".format(r + 1, args.binary))
            print_tables(times, results.get("context", {}), collect(results, "faults"))
            rounds.append(times)
            if old is not None:
                pairs.append((old, times))
        print_summary(rounds)
        if pairs:
            print_paired(pairs)
        return
    if args.json:
        with open(args.json) as f:
            results = json.load(f)
    elif args.binary:
        results = run_benchmarks(args.binary, args.large, args.repetitions, args.extra, args.one_process)
        if args.save:
            with open(args.save, "w") as f:
                json.dump(results, f, indent=1)
    else:
        parser.error("give the benchmark executable or --json FILE")
    times = collect(results)
    if not times:
        sys.exit("no SurfaceNets/VTK extraction results found")
    print_tables(times, results.get("context", {}), collect(results, "faults"))


if __name__ == "__main__":
    main()

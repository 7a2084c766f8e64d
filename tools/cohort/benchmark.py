#!/usr/bin/env python3
"""Benchmark of meshextraction-cohort (not a test): throughput of 1 and 2 LocalCluster workers
on a synthetic cohort, the overhead per case, and, with --head-ct, the time and memory of one
real head CT, from which doc/cohort.md estimates a cohort of 1,000 on N workers; with
--shape-model-meshes N, the shape model of N synthetic meshes on 1 and 2 workers.

  /usr/bin/python3 tools/cohort/benchmark.py --meshextraction build/examples/meshextraction \\
      [--count 24] [--size-range 112 160] [--options '--quality high'] [--repeats 2] \\
      [--head-ct results/data/cranium.nhdr --head-ct-iso 300] [--shape-model-meshes 12]

Every case runs the tool with --threads 1 (the tool's own threads would otherwise use the
cores the second worker is meant to use). Figures per run:
  span         first task start to last task end (without the cluster's start and stop)
  end to end   the whole command, cluster start and stop, verification and report included
  speedup      cases per second of the span, 2 workers over 1
  Dask         per case, worker time outside any task: span x workers - sum of task times
  wrapper      per case, task time outside the tool: attempt folder, setpriv/time, renames,
               the checksum of the mesh
  vs serial    per case, the 1-worker span minus the same commands run one after another
               without Dask or the wrapper
  tool CPU/wall  the tool's CPU time over its wall time: below 1 when other processes take
               the cores (a shared machine), which lowers the speedup
"""

import argparse
import csv
import json
import os
import shlex
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "tests"))
sys.path.insert(0, HERE)

import synthetic  # noqa: E402
from meshextraction_cohort import manifest  # noqa: E402


def run_cohort(tool, manifest_path, outdir, workers, options):
    command = [sys.executable, os.path.join(HERE, "meshextraction-cohort"), "run", manifest_path, outdir]
    command += ["--meshextraction", tool, "--workers", str(workers), "--force", "--options", options]
    started = time.monotonic()
    result = subprocess.run(command, capture_output=True, text=True)
    end_to_end = time.monotonic() - started
    if result.returncode != 0:
        sys.exit(f"benchmark: the run failed:\n{result.stdout}\n{result.stderr}")
    records = []
    for row in json.load(open(os.path.join(outdir, "summary.json")))["cases"]:
        path = os.path.join(outdir, "cases", row["case"], f"{row['case']}.result.json")
        records.append(json.load(open(path)))
    return end_to_end, records


def measures(records, workers, end_to_end):
    span = max(r["started"] + r["wall_seconds"] for r in records) - min(r["started"] for r in records)
    task = sum(r["wall_seconds"] for r in records)
    tool = sum(s["seconds"] for r in records for s in r["steps"])
    n = len(records)
    return {
        "workers": workers,
        "cases": n,
        "end_to_end": end_to_end,
        "span": span,
        "cases_per_second": n / span,
        "dask_per_case": (span * workers - task) / n,
        "wrapper_per_case": (task - tool) / n,
        "tool_per_case": tool / n,
        "tool_cpu_share": sum(s["cpu_seconds"] for r in records for s in r["steps"]) / tool,
        "max_rss_mb": max(r["max_rss_mb"] for r in records),
    }


def serial_reference(tool, cases, options, directory):
    """The same extract and quality commands, one after another, without Dask or the wrapper."""
    started = time.monotonic()
    for case in cases:
        for surface in case.surfaces():
            mesh = os.path.join(directory, f"{surface.name}.vtk")
            extract = [tool, "extract", case.image, mesh, "--threads", "1", *surface.arguments, *options]
            subprocess.run(extract, check=True, capture_output=True)
            measure = [tool, "quality", mesh, "--json", os.path.join(directory, f"{surface.name}.json")]
            env = dict(os.environ, ITK_GLOBAL_DEFAULT_NUMBER_OF_THREADS="1")
            subprocess.run(measure, check=True, capture_output=True, env=env)
    return time.monotonic() - started


def synthetic_benchmark(args):
    work = args.work
    manifest_path = synthetic.make_cohort(
        args.meshextraction, os.path.join(work, "cohort"), args.count, tuple(args.size_range), seed=35, corrupt=False
    )
    cases = manifest.read_manifest(manifest_path)
    options = shlex.split(args.options)
    serial = min(
        serial_reference(args.meshextraction, cases, options, tempfile.mkdtemp(dir=work)) for _ in range(args.repeats)
    )
    runs = {1: [], 2: []}
    for _ in range(args.repeats):
        for workers in (1, 2):
            end_to_end, records = run_cohort(
                args.meshextraction, manifest_path, os.path.join(work, f"out-{workers}"), workers, args.options
            )
            runs[workers].append(measures(records, workers, end_to_end))
    best = {w: min(r, key=lambda m: m["span"]) for w, r in runs.items()}
    print(
        f"synthetic cohort: {len(cases)} cases, sizes {args.size_range[0]}-{args.size_range[1]} voxels per axis, "
        f"extract options '{args.options} --threads 1'; best of {args.repeats} runs"
    )
    print(f"serial reference (the same commands, no Dask): {serial:.2f} s, {serial / len(cases):.3f} s per case")
    print(
        "workers  span s  end-to-end s  cases/s  speedup  tool s/case  tool CPU/wall  wrapper s/case  Dask s/case"
        "  vs serial s/case"
    )
    for workers in (1, 2):
        m = best[workers]
        speedup = m["cases_per_second"] / best[1]["cases_per_second"]
        vs_serial = (best[1]["span"] - serial) / len(cases) if workers == 1 else float("nan")
        print(
            f"{workers:>7}  {m['span']:6.2f}  {m['end_to_end']:12.2f}  {m['cases_per_second']:7.2f}  {speedup:7.2f}"
            f"  {m['tool_per_case']:11.3f}  {m['tool_cpu_share']:13.2f}  {m['wrapper_per_case']:14.4f}"
            f"  {m['dask_per_case']:11.4f}"
            f"  {vs_serial:16.4f}"
        )
    print(
        "all runs (span s): "
        + "; ".join(f"{w} worker(s): " + ", ".join(f"{m['span']:.2f}" for m in runs[w]) for w in (1, 2))
    )
    return best


def head_ct_benchmark(args):
    """One case of the real head CT on one single-threaded worker: the tool's time and peak
    memory per step, the task's overhead."""
    directory = os.path.join(args.work, "head-ct")
    os.makedirs(directory, exist_ok=True)
    manifest_path = os.path.join(directory, "manifest.csv")
    with open(manifest_path, "w", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["case", "image", "iso"])
        writer.writerow(["head-ct", os.path.abspath(args.head_ct), args.head_ct_iso])
    end_to_end, records = run_cohort(
        args.meshextraction, manifest_path, os.path.join(directory, "out"), 1, args.head_ct_options
    )
    record = records[0]
    surface = record["surfaces"][0]
    print(f"head CT {args.head_ct}, extract --iso {args.head_ct_iso} {args.head_ct_options} --threads 1:")
    for step in record["steps"]:
        print(
            f"  {step['step']}: {step['seconds']:.2f} s, CPU {step['cpu_seconds']:.2f} s, "
            f"peak memory {step['max_rss_mb']:.0f} MB"
        )
    print(
        f"  task {record['wall_seconds']:.2f} s, end to end {end_to_end:.2f} s; mesh {surface['triangles']} triangles, "
        f"{surface['mesh_bytes'] / 1e6:.1f} MB; q_area {surface['q_area_mean']:.4f}, valid {surface['valid']}"
    )
    return record, end_to_end


def estimate(record, best, cases=1000):
    """What a cohort of such scans would take on N workers with a core each: the measured task
    time plus the measured Dask overhead per case, divided over the workers; and the data
    the shared file system moves."""
    per_case = record["wall_seconds"] + max(best[1]["dask_per_case"], 0.0)
    memory = record["max_rss_mb"]
    image = os.path.getsize(record["image"]) if os.path.isfile(record["image"]) else 0
    raw = os.path.splitext(record["image"])[0] + ".raw"
    image += os.path.getsize(raw) if os.path.isfile(raw) else 0
    written = record["surfaces"][0]["mesh_bytes"]
    print(
        f"estimate for {cases} such scans, one single-threaded worker per core: {per_case:.1f} s per case, "
        f"{cases * per_case / 3600:.2f} core-hours; peak {memory:.0f} MB per task plus the worker process; "
        f"{cases * image / 1e9:.1f} GB read, {cases * written / 1e9:.1f} GB of meshes written"
    )
    for workers in (1, 8, 32, 128):
        seconds = cases * per_case / workers
        rate = workers / per_case * (image + written) / 1e6
        print(f"  {workers:>4} workers: {seconds / 3600:6.2f} h, {rate:6.1f} MB/s to and from the shared file system")


def shape_model_benchmark(args):
    """`shape-model` (--force) of N synthetic closed meshes on 1 and 2 workers: the end-to-end
    time, the steps' own time, and the speedup."""
    cells = [args.shape_model_cells + k % 5 for k in range(args.shape_model_meshes)]
    meshes = synthetic.make_shape_population(os.path.join(args.work, "shapes"), cells=cells)
    print(f"shape model of {len(meshes)} meshes of {6 * min(cells) ** 2 + 2}-{6 * max(cells) ** 2 + 2} vertices:")
    print("workers  end-to-end s  steps s  steps  speedup")
    first = None
    for workers in (1, 2):
        outdir = os.path.join(args.work, f"shape-model-{workers}")
        command = [sys.executable, os.path.join(HERE, "meshextraction-cohort"), "shape-model", *meshes, outdir]
        command += ["--meshextraction", args.meshextraction, "--workers", str(workers), "--force"]
        started = time.monotonic()
        result = subprocess.run(command, capture_output=True, text=True)
        end_to_end = time.monotonic() - started
        if result.returncode != 0:
            sys.exit(f"benchmark: the shape model failed:\n{result.stdout}\n{result.stderr}")
        steps = json.load(open(os.path.join(outdir, "shape-model.json")))["steps"]
        first = first or end_to_end
        seconds = sum(step["wall_seconds"] for step in steps)
        print(f"{workers:>7}  {end_to_end:12.2f}  {seconds:7.2f}  {len(steps):5}  {first / end_to_end:7.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--meshextraction", required=True)
    parser.add_argument("--work", default=None, help="scratch folder (default: a new temporary one)")
    parser.add_argument("--count", type=int, default=24)
    parser.add_argument("--size-range", type=int, nargs=2, default=(112, 160))
    parser.add_argument("--options", default="--quality high")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--head-ct", help="e.g. results/data/cranium.nhdr (scripts/prepare-data.sh makes it)")
    parser.add_argument("--head-ct-iso", default="300")
    parser.add_argument("--head-ct-options", default="--quality high")
    parser.add_argument("--shape-model-meshes", type=int, default=0, help="also the shape model of this many meshes")
    parser.add_argument("--shape-model-cells", type=int, default=20, help="their resolution (6 cells^2 + 2 vertices)")
    args = parser.parse_args()
    args.meshextraction = os.path.abspath(args.meshextraction)
    args.work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="cohort-benchmark-"))
    os.makedirs(args.work, exist_ok=True)
    print(
        f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())} on {os.cpu_count()} cores "
        "(other processes take cores from the workers)"
    )
    best = synthetic_benchmark(args)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    if args.head_ct:
        record, _ = head_ct_benchmark(args)
        estimate(record, best)
    if args.shape_model_meshes:
        shape_model_benchmark(args)


if __name__ == "__main__":
    main()

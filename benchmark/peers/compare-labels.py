#!/usr/bin/env python3
"""Label images side by side: VTK's vtkSurfaceNets3D and vtkDiscreteFlyingEdges3D (PyPI `vtk`,
pinned in requirements.txt) against the module's SNA and high-quality mode on the same masks.

  bash scripts/compare-labels.sh            (makes the venv, builds, runs this)
  python benchmark/peers/compare-labels.py --meshextraction build/examples/meshextraction \\
      --benchmarks build/benchmark/MeshExtractionBenchmarks [--sizes 128 256] [--out DIR]

A second table: a synthetic map of 100 labels (Voronoi cells in a ball, --many-labels N, 256³
by default): VTK's filters over all labels in one pass against the module's one-pass filter
(MultiLabelSurfaceNetsImageToMeshFilter, its benchmark Labels/MultiLabel on the same map) and
`extract --all-labels` (one closed surface per label, each checked valid).

Masks: the module's sphere phantom (`phantom sphere --image-mode mask`, radius 0.3 N, 1 mm
voxels). Every mesh is measured by one tool, `meshextraction quality`, against the exact sphere:
q_angle, q_area, vertex error mean/max (voxels), enclosed volume against the voxel count, and
validity (closed, 2-manifold, consistently outward, no self-intersection). Times are the
filters' alone, median of --runs runs after a warm-up: VTK's in this process on 1 and 2 threads
(STDThread backend), the module's from its Google Benchmark (Labels/SNA, Labels/HQ), which
runs the same filter on the same sphere with 1 and 2 work units.
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
import zlib

import numpy as np
import vtk
from vtk.util import numpy_support


def read_mask(path):
    """A MetaImage mask written by `meshextraction phantom` (uchar, zlib or raw)."""
    raw = open(path, "rb").read()
    marker = b"ElementDataFile = LOCAL\n"
    start = raw.index(marker) + len(marker)
    header = raw[:start].decode()
    data = raw[start:]
    if "CompressedData = True" in header:
        data = zlib.decompress(data)
    dims = [int(v) for v in header.split("DimSize = ")[1].split("\n")[0].split()]
    return np.frombuffer(data, np.uint8).reshape(dims[::-1])


def vtk_image(mask):
    image = vtk.vtkImageData()
    image.SetDimensions(mask.shape[2], mask.shape[1], mask.shape[0])
    image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(mask.ravel(), deep=1))
    return image


def run_vtk(name, image, threads, runs):
    vtk.vtkSMPTools.SetBackend("STDThread")
    vtk.vtkSMPTools.Initialize(threads)
    times = []
    output = None
    for run in range(runs + 1):
        f = vtk.vtkSurfaceNets3D() if name == "vtkSurfaceNets3D" else vtk.vtkDiscreteFlyingEdges3D()
        f.SetInputData(image)
        f.SetValue(0, 1)
        start = time.perf_counter()
        f.Update()
        if run > 0:  # the first run warms up
            times.append(1000.0 * (time.perf_counter() - start))
        output = f.GetOutput()
    return statistics.median(times), output


def write_vtk_mesh(polydata, path):
    triangles = vtk.vtkTriangleFilter()  # vtkSurfaceNets3D may emit quads; the module reads triangles
    triangles.SetInputData(polydata)
    clean = vtk.vtkPolyData()
    triangles.Update()
    clean.SetPoints(triangles.GetOutput().GetPoints())
    clean.SetPolys(triangles.GetOutput().GetPolys())  # geometry only: no cell data
    writer = vtk.vtkPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(clean)
    writer.Write()


def measure(tool, mesh, mask_path, voxels, workdir):
    report = os.path.join(workdir, "quality.json")
    subprocess.run([tool, "quality", mesh, "--phantom", "sphere", "--image", mask_path, "--json", report],
                   check=True, capture_output=True)
    r = json.load(open(report))[0]
    q, d = r["quality"], r["distance"]["vertices"]
    return {
        "q_angle": q["q_angle"]["mean"],
        "q_area": q["q_area"]["mean"],
        "error_mean": d["mean"],
        "error_max": d["max"],
        "signed_mean": d["signed_mean"],
        "volume_vs_voxels_percent": 100.0 * (q["enclosed_volume"] / voxels - 1.0),
        "valid": bool(q["valid_closed_surface"]),
        "inconsistent_edges": q.get("inconsistently_oriented_edges", 0),
    }


def module_times(benchmarks, sizes):
    """Filter times (ms) of Labels/SNA and Labels/HQ by (method, size, threads)."""
    pattern = "Labels/(SNA|HQ)/size:(" + "|".join(str(n) for n in sizes) + ")/"
    out = subprocess.run([benchmarks, "--benchmark_filter=" + pattern, "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        parts = dict(p.split(":") for p in b["name"].split("/")[2:] if ":" in p)
        method = b["name"].split("/")[1]
        times[(method, int(parts["size"]), int(parts["threads"]))] = b["real_time"]
    return times


def voronoi_labels(n, count, seed=1):
    """`count` labels: the Voronoi cells of random seeds, inside a ball of radius 0.4 n."""
    rng = np.random.default_rng(seed)
    seeds = rng.uniform(0.15 * n, 0.85 * n, (count, 3))
    z, y, x = np.mgrid[:n, :n, :n].astype(np.float32)
    best = np.full((n, n, n), np.inf, np.float32)
    labels = np.zeros((n, n, n), np.uint16)
    for i, (sx, sy, sz) in enumerate(seeds):
        d = (x - sx) ** 2 + (y - sy) ** 2 + (z - sz) ** 2
        closer = d < best
        best[closer] = d[closer]
        labels[closer] = i + 1
    c = 0.5 * (n - 1)
    labels[(x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 > (0.4 * n) ** 2] = 0
    return labels


def write_mha(path, a, spacing=(1, 1, 1), origin=(0, 0, 0)):
    with open(path, "wb") as f:
        f.write("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                "ElementSpacing = {} {} {}\nOffset = {} {} {}\nDimSize = {} {} {}\nElementType = MET_USHORT\n"
                "ElementDataFile = LOCAL\n".format(*spacing, *origin, a.shape[2], a.shape[1], a.shape[0]).encode())
        f.write(np.ascontiguousarray(a, np.uint16).tobytes())


def multi_label_filter_times(benchmarks, path):
    """The module's one-pass filter (Labels/MultiLabel: its size names the built-in map, the
    map at `path` replaces it) on 1 and 2 threads (ms)."""
    out = subprocess.run([benchmarks, "--benchmark_filter=Labels/MultiLabel/",
                          "--benchmark_format=json", "--benchmark_repetitions=3"],
                         check=True, capture_output=True, text=True,
                         env=dict(os.environ, MESHEXTRACTION_LABEL_MAP=path)).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("aggregate_name") == "median":
            threads = int(dict(p.split(":") for p in b["name"].split("/")[2:] if ":" in p)["threads"])
            times[threads] = (b["real_time"], int(b.get("triangles", 0)))
    return times


def vtk_all_labels(name, image, present, runs, triangles=False):
    """VTK's filter `name` over every label at once on 1 and 2 threads: the best time (ms) of
    runs // 5 runs each, and the last output (triangles only if asked: vtkSurfaceNets3D)."""
    vtk.vtkSMPTools.SetBackend("STDThread")
    times = []
    output = None
    for threads in (1, 2):
        vtk.vtkSMPTools.Initialize(threads)
        best = None
        for run in range(max(1, runs // 5)):
            f = vtk.vtkSurfaceNets3D() if name == "vtkSurfaceNets3D" else vtk.vtkDiscreteFlyingEdges3D()
            f.SetInputData(image)
            for k, value in enumerate(present):
                f.SetValue(k, value)
            if triangles:
                f.SetOutputMeshTypeToTriangles()
            start = time.perf_counter()
            f.Update()
            elapsed = 1000.0 * (time.perf_counter() - start)
            best = elapsed if best is None else min(best, elapsed)
            output = f.GetOutput()
        times.append(best)
    return times, output


def many_labels(tool, benchmarks, workdir, n, count, runs):
    """The synthetic label map: VTK's filters over every label at once, and the module's
    one-pass filter (its benchmark on the same map) and extract --all-labels (the command's
    wall-clock time, reading and writing included: one pass with shared faces by default,
    --separate-labels and --quality high each label on its own), each label's surface
    checked by `quality --require-valid`."""
    labels = voronoi_labels(n, count)
    present = [int(v) for v in np.unique(labels) if v > 0]
    path = os.path.join(workdir, "voronoi{}.mha".format(n))
    write_mha(path, labels)
    image = vtk_image(labels)
    print("\n{} labels (Voronoi cells in a ball), {}³:\n".format(len(present), n))
    print("| method | ms 1 thread / 2 | triangles | per-label surfaces valid |")
    print("|---|---|---|---|")
    for name in ("vtkSurfaceNets3D", "vtkDiscreteFlyingEdges3D"):
        times, output = vtk_all_labels(name, image, present, runs)
        print("| {} (VTK {}, one pass) | {:.0f} / {:.0f} | {} | not measured |".format(
            name, vtk.vtkVersion.GetVTKVersion(), times[0], times[1], output.GetNumberOfCells()))
    filter_times = multi_label_filter_times(benchmarks, path)
    if 1 in filter_times:
        print("| module MultiLabelSurfaceNetsImageToMeshFilter (filter alone, one pass) | {:.0f} / {:.0f} | {} | "
              "(below) |".format(filter_times[1][0], filter_times.get(2, (float("nan"), 0))[0], filter_times[1][1]))
    for label, options in (("one pass, shared faces", []), ("--separate-labels", ["--separate-labels"]),
                           ("--quality high", ["--quality", "high"])):
        out = os.path.join(workdir, "voronoi-" + (options[-1].strip("-") if options else "shared"))
        os.makedirs(out, exist_ok=True)
        times = []
        for threads in (1, 2):
            start = time.perf_counter()
            subprocess.run([tool, "extract", path, os.path.join(out, "v.vtp"), "--all-labels",
                            "--threads", str(threads)] + options, check=True, capture_output=True)
            times.append(1000.0 * (time.perf_counter() - start))
        meshes = sorted(os.path.join(out, m) for m in os.listdir(out) if m.endswith(".vtp"))
        check = subprocess.run([tool, "quality"] + meshes + ["--no-self-intersections", "--require-valid"],
                               capture_output=True, text=True)
        triangles = sum(int(m.group(1)) for m in re.finditer(r"\), triangles (\d+),", check.stdout))
        print("| module extract --all-labels, {} (whole command) | {:.0f} / {:.0f} | {} (the labels' surfaces) | "
              "{} of {} |".format(label, times[0], times[1], triangles or "-",
                                  len(meshes) if check.returncode == 0 else "not all", len(meshes)))


def surface_quality(tool, meshes, workdir):
    """Per mesh: q_angle, q_area, and its defects (`meshextraction quality`, exact
    self-intersections)."""
    report = os.path.join(workdir, "quality-labels.json")
    subprocess.run([tool, "quality"] + meshes + ["--json", report], check=True, capture_output=True)
    rows = []
    for r in json.load(open(report)):
        q = r["quality"]
        rows.append(dict(mesh=os.path.basename(r["mesh"]), triangles=q["triangles"], q_angle=q["q_angle"]["mean"],
                         q_area=q["q_area"]["mean"], non_manifold=q["non_manifold_edges"] + q["non_manifold_vertices"],
                         inconsistent=q["inconsistently_oriented_edges"], crossing=q["self_intersecting_pairs"],
                         valid=bool(q["valid_closed_surface"])))
    return rows


def vtk_label_surfaces(output, labels, prefix):
    """Each label's surface from vtkSurfaceNets3D's output: the faces whose BoundaryLabels
    name it, turned where it is the second label (VTK 9.6+ points a face out of the first)."""
    boundary = numpy_support.vtk_to_numpy(output.GetCellData().GetArray("BoundaryLabels"))
    points = output.GetPoints()
    polys = numpy_support.vtk_to_numpy(output.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    paths = []
    for label in labels:
        first = boundary[:, 0] == label
        second = boundary[:, 1] == label
        triangles = np.concatenate([polys[first], polys[second][:, ::-1]])
        cells = vtk.vtkCellArray()
        for t in triangles:
            cells.InsertNextCell(3, [int(v) for v in t])
        mesh = vtk.vtkPolyData()
        mesh.SetPoints(points)
        mesh.SetPolys(cells)
        clean = vtk.vtkCleanPolyData()  # only the points the label's faces use
        clean.SetInputData(mesh)
        clean.PointMergingOff()
        clean.Update()
        path = "{}-{}.vtk".format(prefix, label)
        write_vtk_mesh(clean.GetOutput(), path)
        paths.append(path)
    return paths


def real_label_map(tool, benchmarks, workdir, name, title, labels, spacing, origin, runs):
    """A real label map: VTK's vtkSurfaceNets3D (every label at once; each label's surface
    taken from its output by BoundaryLabels) against the module's one-pass filter; each
    label's surface measured by `meshextraction quality` (the table sums over the labels)."""
    path = os.path.join(workdir, name + "-labels.mha")
    write_mha(path, labels, spacing, origin)
    dims = labels.shape[::-1]
    label_image = vtk.vtkImageData()
    label_image.SetDimensions(dims)
    label_image.SetSpacing(spacing)
    label_image.SetOrigin(origin)
    label_image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(np.ascontiguousarray(labels).ravel(), deep=1))
    present = [int(v) for v in np.unique(labels) if v > 0]
    print("\n{} ({} labels):\n".format(title, len(present)))
    print("| method | ms 1 thread / 2 | labels valid | triangles | q_angle | q_area | non-manifold | inconsistent edges |"
          " crossing pairs |")
    print("|---|---|---|---|---|---|---|---|---|")
    times, output = vtk_all_labels("vtkSurfaceNets3D", label_image, present, runs, triangles=True)
    vtk_rows = surface_quality(tool, vtk_label_surfaces(output, present, os.path.join(workdir, name + "-vtk")), workdir)
    filter_times = multi_label_filter_times(benchmarks, path)
    out = os.path.join(workdir, name + "-module")
    os.makedirs(out, exist_ok=True)
    subprocess.run([tool, "extract", path, os.path.join(out, "l.vtk"), "--all-labels"], check=True,
                   capture_output=True)
    module_rows = surface_quality(tool, [os.path.join(out, "l-{}.vtk".format(label)) for label in present], workdir)
    module_times = [filter_times.get(t, (float("nan"),))[0] for t in (1, 2)]
    for method, t, rows in (("vtkSurfaceNets3D (VTK {})".format(vtk.vtkVersion.GetVTKVersion()), times, vtk_rows),
                            ("module one pass", module_times, module_rows)):
        triangles = sum(r["triangles"] for r in rows)
        print("| {} | {:.0f} / {:.0f} | {} of {} | {} | {:.3f} | {:.3f} | {} | {} | {} |".format(
            method, t[0], t[1], sum(r["valid"] for r in rows), len(rows), triangles,
            sum(r["q_angle"] * r["triangles"] for r in rows) / triangles,
            sum(r["q_area"] * r["triangles"] for r in rows) / triangles,
            sum(r["non_manifold"] for r in rows), sum(r["inconsistent"] for r in rows),
            sum(r["crossing"] for r in rows)))


def read_image(path):
    """An image VTK reads (NRRD, NIfTI) as a NumPy array (z, y, x), its spacing and origin."""
    reader = vtk.vtkNIFTIImageReader() if path.endswith((".nii", ".nii.gz")) else vtk.vtkNrrdReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    values = numpy_support.vtk_to_numpy(image.GetPointData().GetScalars()).reshape(image.GetDimensions()[::-1])
    return values, image.GetSpacing(), image.GetOrigin()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--meshextraction", required=True)
    parser.add_argument("--benchmarks", required=True, help="MeshExtractionBenchmarks executable")
    parser.add_argument("--sizes", type=int, nargs="+", default=[128, 256])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--out", default=None, help="folder for the masks, meshes and results.json")
    parser.add_argument("--many-labels", type=int, default=256, help="size of the 100-label volume (0: none)")
    parser.add_argument("--head-ct", default=None,
                        help="the head CT (cranium.nhdr of scripts/prepare-data.sh) for the soft tissue and bone table")
    parser.add_argument("--atlas", default=None,
                        help="a label atlas (e.g. mricron-data's aal.nii.gz) for a real many-label table")
    parser.add_argument("--only-many-labels", action="store_true", help="skip the sphere table")
    args = parser.parse_args()
    workdir = args.out or tempfile.mkdtemp(prefix="meshextraction-labels-")
    os.makedirs(workdir, exist_ok=True)
    tool = args.meshextraction
    times = module_times(args.benchmarks, args.sizes) if not args.only_many_labels else {}
    rows = []
    for n in ([] if args.only_many_labels else args.sizes):
        mask_path = os.path.join(workdir, f"sphere{n}.mha")
        subprocess.run([tool, "phantom", "sphere", mask_path, "--size", str(n), "--image-mode", "mask"],
                       check=True, capture_output=True)
        mask = read_mask(mask_path)
        voxels = float(mask.sum())
        image = vtk_image(mask)
        for name in ("vtkSurfaceNets3D", "vtkDiscreteFlyingEdges3D"):
            t1, output = run_vtk(name, image, 1, args.runs)
            t2, _ = run_vtk(name, image, 2, args.runs)
            mesh = os.path.join(workdir, f"{name}-{n}.vtk")
            write_vtk_mesh(output, mesh)
            rows.append(dict(size=n, method=name + " (VTK " + vtk.vtkVersion.GetVTKVersion() + ")",
                             ms_1=t1, ms_2=t2, **measure(tool, mesh, mask_path, voxels, workdir)))
        for method, options in (("SNA", []), ("HQ", ["--quality", "high"])):
            mesh = os.path.join(workdir, f"module-{method}-{n}.vtk")
            subprocess.run([tool, "extract", mask_path, mesh, "--label", "1"] + options,
                           check=True, capture_output=True)
            rows.append(dict(size=n, method="module " + ("SNA on labels" if method == "SNA" else "--quality high"),
                             ms_1=times.get((method, n, 1), float("nan")),
                             ms_2=times.get((method, n, 2), float("nan")),
                             **measure(tool, mesh, mask_path, voxels, workdir)))
    print("| N | method | q_angle | q_area | vertex error mean / max (voxels) | signed | volume vs voxels |"
          " valid, outward | ms 1 thread / 2 | speed-up |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        valid = "yes" if r["valid"] else f"no ({r['inconsistent_edges']} inconsistent edges)"
        print(f"| {r['size']} | {r['method']} | {r['q_angle']:.3f} | {r['q_area']:.3f} | "
              f"{r['error_mean']:.3f} / {r['error_max']:.3f} | {r['signed_mean']:+.3f} | "
              f"{r['volume_vs_voxels_percent']:+.2f} % | {valid} | {r['ms_1']:.1f} / {r['ms_2']:.1f} | "
              f"{r['ms_1'] / r['ms_2']:.2f}x |")
    json.dump(rows, open(os.path.join(workdir, "results.json"), "w"), indent=1)
    if args.many_labels > 0:
        many_labels(tool, args.benchmarks, workdir, args.many_labels, 100, args.runs)
    if args.head_ct:
        values, spacing, origin = read_image(args.head_ct)
        real_label_map(tool, args.benchmarks, workdir, "head-ct",
                       "Head CT (invesalius-examples) as labels: soft tissue [-300, 300) HU = 1, bone >= 300 HU = 2",
                       np.digitize(values, (-300, 300)).astype(np.uint16), spacing, origin, args.runs)
    if args.atlas:
        values, spacing, origin = read_image(args.atlas)
        real_label_map(tool, args.benchmarks, workdir, "atlas", "Label atlas " + os.path.basename(args.atlas),
                       values.astype(np.uint16), spacing, origin, args.runs)
    print(f"\nmeshes and results.json in {workdir}", file=sys.stderr)


if __name__ == "__main__":
    main()

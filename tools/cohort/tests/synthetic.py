"""A synthetic cohort for the tests and the benchmark: phantoms of random shapes, grid sizes,
spacings, pixel types and image kinds, made by `meshextraction phantom`, plus (optionally)
one corrupt image, and the CSV manifest that lists them. And a population of closed meshes
for shape models (make_shape_population).

  python3 synthetic.py MESHEXTRACTION DIR [--count N] [--size-range LO HI] [--seed S] [--no-corrupt]
"""

import argparse
import csv
import math
import os
import random
import subprocess

SHAPES = ("sphere", "ellipsoid", "torus", "two-spheres", "indented-sphere", "chapter4-sphere")


def _spec(rng, index, size_range):
    """One random case: the phantom command's options and the manifest's fields."""
    shape = SHAPES[index % len(SHAPES)] if index < len(SHAPES) else rng.choice(SHAPES)
    size = "x".join(str(rng.randint(*size_range)) for _ in range(3))
    spacing = "x".join(f"{rng.uniform(0.7, 1.5):.3f}" for _ in range(3))
    options = ["--size", size, "--spacing", spacing]
    row = {"case": f"case-{index:03d}-{shape}"}
    if shape == "chapter4-sphere":
        options += ["--pixel-type", "short", "--edge-width", "1"]
        row.update(iso="50", inside="above")
    elif rng.random() < 0.25:
        label = str(rng.randint(1, 5))
        options += ["--image-mode", "mask", "--inside", label]
        row.update(label=label)
    elif rng.random() < 0.3:
        options += ["--pixel-type", "short", "--distance-scale", "10"]
        row.update(iso="0", inside="below")
    else:
        row.update(iso="0", inside="below")
    return shape, options, row


# The case whose image is cut short: it fails on every attempt.
CORRUPT_CASE = "corrupt"


def make_cohort(tool, directory, count=20, size_range=(24, 40), seed=35, corrupt=True):
    """Writes DIR/images/*.nrrd and DIR/manifest.csv; returns the manifest's path."""
    rng = random.Random(seed)
    images = os.path.join(directory, "images")
    os.makedirs(images, exist_ok=True)
    rows = []
    for index in range(count):
        shape, options, row = _spec(rng, index, size_range)
        image = os.path.join(images, f"{row['case']}.nrrd")
        subprocess.run([tool, "phantom", shape, image] + options, check=True, capture_output=True)
        row["image"] = os.path.relpath(image, directory)
        rows.append(row)
    if corrupt:
        # A scan cut short in transfer: the header of a valid image, half of its data.
        with open(os.path.join(images, f"{rows[0]['case']}.nrrd"), "rb") as stream:
            data = stream.read()
        with open(os.path.join(images, f"{CORRUPT_CASE}.nrrd"), "wb") as stream:
            stream.write(data[: len(data) // 2])
        rows.insert(
            len(rows) // 2,
            {"case": CORRUPT_CASE, "image": f"images/{CORRUPT_CASE}.nrrd", "iso": "0", "inside": "below"},
        )
    manifest = os.path.join(directory, "manifest.csv")
    with open(manifest, "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=("case", "image", "iso", "inside", "label", "options"))
        writer.writeheader()
        writer.writerows(rows)
    return manifest


def _cube_sphere(cells):
    """The unit sphere as a cube's six faces of cells x cells squares (two triangles each),
    pushed out to the sphere: 6 cells^2 + 2 vertices. Returns (points, triangles)."""
    index, points, triangles = {}, [], []

    def vertex(key):
        if key not in index:
            index[key] = len(points)
            norm = math.sqrt(sum(k * k for k in key))
            points.append([k / norm for k in key])
        return index[key]

    steps = range(-cells, cells, 2)
    for axis in range(3):
        for side in (-cells, cells):
            for u in steps:
                for v in steps:
                    corners = []
                    for du, dv in ((0, 0), (2, 0), (2, 2), (0, 2)):
                        key = [0, 0, 0]
                        key[axis], key[(axis + 1) % 3], key[(axis + 2) % 3] = side, u + du, v + dv
                        corners.append(vertex(tuple(key)))
                    triangles += [(corners[0], corners[1], corners[2]), (corners[0], corners[2], corners[3])]
    oriented = []
    for a, b, c in triangles:  # outward: the normal along the centroid (the sphere is star-shaped)
        p, q, r = points[a], points[b], points[c]
        e, f = [q[k] - p[k] for k in range(3)], [r[k] - p[k] for k in range(3)]
        normal = (e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0])
        outward = sum(normal[k] * (p[k] + q[k] + r[k]) for k in range(3)) > 0
        oriented.append((a, b, c) if outward else (a, c, b))
    return points, oriented


def _rotation(rng):
    """A random rotation matrix (from a random unit quaternion)."""
    w, x, y, z = (rng.gauss(0, 1) for _ in range(4))
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]


def write_ply(path, points, triangles):
    """An ASCII PLY with double coordinates (repr: exact)."""
    with open(path, "w") as stream:
        stream.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\n")
        stream.write("property double x\nproperty double y\nproperty double z\n")
        stream.write(f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n")
        stream.writelines(f"{p[0]!r} {p[1]!r} {p[2]!r}\n" for p in points)
        stream.writelines(f"3 {a} {b} {c}\n" for a, b, c in triangles)


# Cells per cube edge of the shape population's meshes: the second and third have the most
# vertices (a tie: the pivot is the first of them).
SHAPE_CELLS = (9, 12, 12, 10, 11)


def make_shape_population(directory, cells=SHAPE_CELLS, seed=3):
    """Closed meshes of ellipsoids with a bump, of random semi-axes (about 11, 8 and 5 mm),
    bump, rotation, position and resolution, written as DIR/shape-K.ply; the third with a
    small separate tetrahedron (prepare drops it), the fourth turned inward (prepare turns
    it outward). Returns the paths."""
    rng = random.Random(seed)
    os.makedirs(directory, exist_ok=True)
    paths = []
    for k, count in enumerate(cells):
        sphere, triangles = _cube_sphere(count)
        axes = [11 * rng.uniform(0.85, 1.15), 8 * rng.uniform(0.85, 1.15), 5 * rng.uniform(0.85, 1.15)]
        bump, rotation = rng.uniform(0.0, 0.25), _rotation(rng)
        offset = [rng.uniform(-20, 20) for _ in range(3)]
        points = []
        for p in sphere:
            # A bump on the +x side: a radial scale of 1 + bump at (1, 0, 0), 1 far from it.
            scale = 1 + bump * math.exp(-((p[0] - 1) ** 2 + p[1] ** 2 + p[2] ** 2) / 0.3)
            q = [axes[i] * p[i] * scale for i in range(3)]
            points.append([sum(rotation[i][j] * q[j] for j in range(3)) + offset[i] for i in range(3)])
        if k == 2:
            base = len(points)
            points += [[60, 60, 60], [61, 60, 60], [60, 61, 60], [60, 60, 61]]
            triangles += [(base + a, base + b, base + c) for a, b, c in ((0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3))]
        if k == 3:
            triangles = [(a, c, b) for a, b, c in triangles]
        paths.append(os.path.join(directory, f"shape-{k}.ply"))
        write_ply(paths[-1], points, triangles)
    return paths


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("tool")
    parser.add_argument("directory")
    parser.add_argument("--count", type=int, default=20)
    parser.add_argument("--size-range", type=int, nargs=2, default=(24, 40))
    parser.add_argument("--seed", type=int, default=35)
    parser.add_argument("--no-corrupt", action="store_true")
    arguments = parser.parse_args()
    print(
        make_cohort(
            arguments.tool,
            arguments.directory,
            arguments.count,
            tuple(arguments.size_range),
            arguments.seed,
            not arguments.no_corrupt,
        )
    )

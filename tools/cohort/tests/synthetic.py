"""A synthetic cohort for the tests and the benchmark: phantoms of random shapes, grid sizes,
spacings, pixel types and image kinds, made by `meshextraction phantom`, plus (optionally)
one corrupt image, and the CSV manifest that lists them.

  python3 synthetic.py MESHEXTRACTION DIR [--count N] [--size-range LO HI] [--seed S] [--no-corrupt]
"""

import argparse
import csv
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

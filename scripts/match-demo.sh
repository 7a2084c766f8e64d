#!/usr/bin/env bash
# The three-landmark incremental match (thesis chapter 6) on a real MRI: the Colin27 T1
# of Debian's mricron-data is moved by a known rigid transform; three landmarks are placed
# in both images with unequal noise (A 0.5 mm, B 1 mm, C 3 mm per coordinate), and
# `meshextraction match` brings the moved image back. Writes OUT/alignment.png (three
# slices through C: fixed in magenta, moving in green; a checkerboard below) and prints
# the landmark residuals of the incremental match and of ITK's least squares, and the
# target registration error at points around C and over the head, of both.
#
#   bash scripts/match-demo.sh [OUT]        (default OUT: results/match)
set -euo pipefail
out=${1:-results/match}
me=${MESHEXTRACTION:-build/examples/meshextraction}
t1=/usr/share/mricron/templates/ch2.nii.gz
if [ ! -f "$t1" ]; then
  echo "match-demo: $t1 is missing (apt install mricron-data)" >&2
  exit 2
fi
mkdir -p "$out"
# Landmarks of the Colin27 T1 in LPS mm (ITK's frame): A near the anterior commissure,
# B at the vertex of the brain, C in the right lateral ventricle. S is the true
# fixed-to-moving transform; the script writes the landmark files for the moving image
# (S(x) + noise) and for making it (S^-1, so that the resampled ch2 is the moving image).
python3 - "$out" <<'EOF'
import json, math, random, sys
out = sys.argv[1]
fixed = {"A": (0.0, -2.0, -4.0), "B": (0.0, 15.0, 75.0), "C": (-20.0, 20.0, 20.0)}
axis = (0.2, 0.3, 1.0); n = math.sqrt(sum(a * a for a in axis)); axis = [a / n for a in axis]
angle = math.radians(12.0)
c, s = math.cos(angle), math.sin(angle)
x, y, z = axis
R = [[c + x*x*(1-c), x*y*(1-c) - z*s, x*z*(1-c) + y*s],
     [y*x*(1-c) + z*s, c + y*y*(1-c), y*z*(1-c) - x*s],
     [z*x*(1-c) - y*s, z*y*(1-c) + x*s, c + z*z*(1-c)]]
shift = (6.0, -4.0, 8.0)
center = fixed["A"]
def S(p):
    d = [p[i] - center[i] for i in range(3)]
    return [sum(R[r][k] * d[k] for k in range(3)) + center[r] + shift[r] for r in range(3)]
def Sinv(q):
    d = [q[i] - center[i] - shift[i] for i in range(3)]
    return [sum(R[k][r] * d[k] for k in range(3)) + center[r] for r in range(3)]
def write(name, points):
    with open(f"{out}/{name}", "w") as f:
        json.dump([{"id": k, "coordinates": list(v)} for k, v in points.items()], f, indent=1)
write("fixed.json", fixed)
write("make-moving.json", {k: Sinv(v) for k, v in fixed.items()})
random.seed(7)
sigma = {"A": 0.5, "B": 1.0, "C": 3.0}
write("moving.json", {k: [S(v)[i] + random.gauss(0.0, sigma[k]) for i in range(3)] for k, v in fixed.items()})
# Points of interest for the TRE: a sphere of radius 10 mm about C, and a shell of
# radius 70 mm about A (roughly the head's surface).
poi = []
for i in range(200):
    zz = 1 - 2 * (i + 0.5) / 200; r = math.sqrt(1 - zz * zz); phi = i * math.pi * (3 - math.sqrt(5))
    d = (r * math.cos(phi), r * math.sin(phi), zz)
    poi.append(("C", [fixed["C"][k] + 10 * d[k] for k in range(3)]))
    poi.append(("head", [fixed["A"][k] + 70 * d[k] for k in range(3)]))
json.dump({"truth": [S(p) for _, p in poi], "points": [p for _, p in poi], "where": [w for w, _ in poi]},
          open(f"{out}/poi.json", "w"))
EOF
echo "== making the moving image: the T1 moved by a known rigid transform" >&2
"$me" match "$t1" "$t1" --fixed-landmarks "$out/fixed.json" --moving-landmarks "$out/make-moving.json" \
  --resampled "$out/moving.nii.gz" > /dev/null
echo "== matching it back from three noisy landmarks" >&2
"$me" match "$t1" "$out/moving.nii.gz" --fixed-landmarks "$out/fixed.json" --moving-landmarks "$out/moving.json" \
  --transform "$out/incremental.tfm" --resampled "$out/aligned.nii.gz" --png "$out/alignment.png"
# The target registration error of the incremental match, from the written transform
# (VersorRigid3DTransform: versor, translation; centre) against the true one.
python3 - "$out" <<'EOF2'
import json, math, sys
out = sys.argv[1]
values = {}
for line in open(f"{out}/incremental.tfm"):
    if ":" in line:
        key, text = line.split(":", 1)
        values[key.strip()] = [float(v) for v in text.split()] if key.strip() != "Transform" else text.strip()
vx, vy, vz, tx, ty, tz = values["Parameters"]
cx, cy, cz = values["FixedParameters"]
w = math.sqrt(max(0.0, 1 - vx * vx - vy * vy - vz * vz))
R = [[1 - 2*(vy*vy + vz*vz), 2*(vx*vy - w*vz), 2*(vx*vz + w*vy)],
     [2*(vx*vy + w*vz), 1 - 2*(vx*vx + vz*vz), 2*(vy*vz - w*vx)],
     [2*(vx*vz - w*vy), 2*(vy*vz + w*vx), 1 - 2*(vx*vx + vy*vy)]]
def T(p):
    d = [p[0] - cx, p[1] - cy, p[2] - cz]
    return [sum(R[r][k] * d[k] for k in range(3)) + (cx, cy, cz)[r] + (tx, ty, tz)[r] for r in range(3)]
poi = json.load(open(f"{out}/poi.json"))
for where in ("C", "head"):
    errors = sorted(math.dist(T(p), q) for p, q, w in zip(poi["points"], poi["truth"], poi["where"]) if w == where)
    print(f"  TRE of the incremental match, {'10 mm about C' if where == 'C' else '70 mm about A'}: "
          f"mean {sum(errors) / len(errors):.2f} mm, 95th percentile {errors[int(0.95 * (len(errors) - 1))]:.2f} mm")
EOF2
echo "== wrote $out/alignment.png" >&2

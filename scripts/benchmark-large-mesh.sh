#!/usr/bin/env bash
# Time and peak memory of `quality`, `improve` and `refine` on a mesh of about two
# million triangles, the way a user runs them (whole commands, reading and writing
# included), and each command's time as a multiple of `quality`'s.
#
# The mesh is the SurfaceNets surface of the Colin27 T1 (Debian's mricron-data,
# /usr/share/mricron/templates/ch2.nii.gz) at 90: 945,014 points, 1,883,004
# triangles; `refine` refines it against the same image. Not a test: run it on an
# idle machine.
#
#   bash scripts/benchmark-large-mesh.sh [build/examples/meshextraction] [WORKDIR]
set -euo pipefail
cd "$(dirname "$0")/.."
me=${1:-build/examples/meshextraction}
image=/usr/share/mricron/templates/ch2.nii.gz
if [ ! -f "$image" ]; then
  echo "benchmark-large-mesh: $image is missing; install Debian's mricron-data" >&2
  exit 2
fi
if [ $# -ge 2 ]; then
  work=$2
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
me=$(realpath "$me")

"$me" extract "$image" "$work/mesh.vtk" --iso 90 > /dev/null 2>&1

measure() { # name, then the command's arguments: prints "name seconds peak-MB"
  local name=$1
  shift
  /usr/bin/time -f "%e %M" -o "$work/time.txt" "$me" "$@" > "$work/$name.log" 2>&1 ||
    { cat "$work/$name.log" >&2; echo "benchmark-large-mesh: $name failed" >&2; exit 1; }
  read -r seconds kb < "$work/time.txt"
  echo "$name $seconds $((kb / 1024))"
}

{
  measure quality quality "$work/mesh.vtk"
  measure improve improve "$work/mesh.vtk" "$work/improved.vtk"
  measure refine refine "$image" "$work/mesh.vtk" "$work/refined.vtk" --cycles 1 --max-deviation 2
} > "$work/results.txt"

triangles=$(grep -m1 -o "[0-9]* triangles" "$work/improve.log" || true)
echo "mesh: ${triangles:-?} (SurfaceNets of ch2.nii.gz at 90)"
awk 'NR == 1 { q = $2 } { printf "%-8s %8.1f s %7d MB  %5.2fx quality\n", $1, $2, $3, $2 / q }' "$work/results.txt"

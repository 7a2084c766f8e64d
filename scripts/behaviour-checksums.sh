#!/usr/bin/env bash
# Extracts, improves and refines a fixed set of inputs with the command-line tool and
# prints the SHA-256 of every mesh written, one "checksum  name" line each, sorted.
# Two builds that print the same lines make byte-identical meshes: this is how a change
# that should not change behaviour (a restructuring) is shown not to.
#
#   bash scripts/behaviour-checksums.sh [MESHEXTRACTION] [WORKDIR] > sums.txt
#
# MESHEXTRACTION defaults to build/examples/meshextraction, WORKDIR to a temporary
# directory (removed afterwards). The inputs are made by the tool itself: the phantoms
# (sphere, two spheres, torus, narrow cleft, an ellipsoid on 1x1x2.5 mm voxels) in SNA,
# SNERT and high quality, a label image, Delaunay and quad faces, Gaussian gradients,
# `improve` (regularity swaps with Laplacian, Taubin and safe smoothing), `refine`
# (a geodesic sphere and a SurfaceNets start on the noisy chapter-4 sphere) and the labels
# of that sphere in one pass.
set -euo pipefail
me=${1:-build/examples/meshextraction}
me=$(cd "$(dirname "$me")" && pwd)/$(basename "$me")
if [ ! -x "$me" ]; then
  echo "behaviour-checksums: $me is not an executable (build the tool first)" >&2
  exit 2
fi
if [ $# -ge 2 ]; then
  work=$2
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
cd "$work"
run() { "$me" "$@" > /dev/null 2> "$work/last.log" || { cat "$work/last.log" >&2; echo "failed: $*" >&2; exit 1; }; }

for shape in sphere two-spheres torus narrow-cleft; do
  run extract --phantom "$shape" --size 48 --relaxation sna "$shape-sna.vtk"
  run extract --phantom "$shape" --size 48 "$shape-snert.vtk"
  run extract --phantom "$shape" --size 48 --quality high "$shape-high.vtk"
done
# Anisotropic voxels, with and without resampling to cubic voxels.
run extract --phantom ellipsoid --size 40x40x20 --spacing 1x1x2.5 "ellipsoid-aniso-snert.vtk"
run extract --phantom ellipsoid --size 40x40x20 --spacing 1x1x2.5 --quality high "ellipsoid-aniso-high.vtk"
run extract --phantom ellipsoid --size 40x40x20 --spacing 1x1x2.5 --quality high --isotropic "ellipsoid-iso-high.vtk"
# Other faces, gradients and iteration settings.
run extract --phantom torus --size 40 --triangulation delaunay "torus-delaunay.vtk"
run extract --phantom torus --size 40 --triangulation quads "torus-quads.vtk"
run extract --phantom sphere --size 40 --sigma 1.5 "sphere-gaussian.vtk"
run extract --phantom two-spheres --size 40 --quality high --cell-dilation 0 --rounds 3 "two-spheres-high-in-cell.vtk"
run extract --phantom sphere --size 32 --relaxation gradient "sphere-gradient.vtk"
# A label image, and a segmentation relaxed toward a greyscale iso-surface.
run phantom torus torus-mask.nrrd --size 40 --image-mode mask
run phantom torus torus-distance.nrrd --size 40
run extract torus-mask.nrrd --label 1 "torus-label-sna.vtk"
run extract torus-mask.nrrd --label 1 --quality high "torus-label-high.vtk"
run extract torus-distance.nrrd --iso 0 --inside below --labels torus-mask.nrrd --label 1 "torus-segmentation.vtk"
# improve: a marching-cubes-like start (no relaxation) smoothed and swapped.
run extract --phantom sphere --size 40 --relaxation none "sphere-none.vtk"
run improve sphere-none.vtk improve-laplacian.vtk --swap regularity --smoothing laplacian --constraint centroid
run improve sphere-none.vtk improve-volume.vtk --swap regularity --volume-preservation --smoothing laplacian
run improve sphere-none.vtk improve-taubin.vtk --smoothing taubin --weights cotangent --swap delaunay
run improve sphere-none.vtk improve-safe.vtk --smoothing laplacian --constraint safe --update immediate --swap none
run improve torus-snert.vtk improve-torus.vtk --swap regularity --smoothing laplacian --weights area
# refine: the ED/ES/S protocol on the noisy chapter-4 sphere.
run phantom chapter4-sphere chapter4.nrrd --size 48 --noise 2 --seed 3
run refine chapter4.nrrd refine-sphere.vtk --initial sphere --radius 8 --subdivisions 3 --max-deviation 3 \
  --target-quality 0.9
run refine chapter4.nrrd refine-surfacenets.vtk --initial surfacenets --iso 50 --max-deviation 2 --cycles 2
run refine torus-distance.nrrd torus-snert.vtk refine-torus.vtk --max-deviation 1.5 --cycles 1
# Every label in one pass: the noisy sphere's shell and core as labels, and all faces once.
run extract chapter4.nrrd multi.vtk --label-thresholds 30,70 --combined multi-combined.vtk

for f in *.vtk; do
  sha256sum "$f"
done | sort -k2

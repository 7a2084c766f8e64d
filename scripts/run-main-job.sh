#!/usr/bin/env bash
# The main job: installs the dependencies, builds, and extracts surfaces from the
# built-in phantoms and from the real head CT of Debian's invesalius-examples, with
# plain SurfaceNets (SNERT) and the high-quality mode; refines a noisy sphere, the CT
# bone surface and the brain surface of the Colin27 T1 MRI (mricron-data) with the
# scale-space protocol; writes the meshes, the comparison with VTK's marching cubes,
# flying edges and 3D Slicer's pipeline, the refinement step tables, and an HTML report
# (results/index.html) with quality tables, histograms and renderings.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dependencies.sh
bash scripts/build.sh
bash scripts/main-job.sh "${1:-results}"

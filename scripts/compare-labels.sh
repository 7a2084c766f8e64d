#!/usr/bin/env bash
# Label images side by side with VTK's vtkSurfaceNets3D and vtkDiscreteFlyingEdges3D (PyPI,
# pinned in benchmark/peers/requirements.txt, in a venv under build/): quality, accuracy,
# validity and filter time (benchmark/peers/compare-labels.py). Usage: compare-labels.sh [OUTDIR]
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/examples/meshextraction ] && [ -x build/benchmark/MeshExtractionBenchmarks ] || bash scripts/build.sh
venv=build/peers-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet -r benchmark/peers/requirements.txt
fi
"$venv/bin/python" benchmark/peers/compare-labels.py --meshextraction build/examples/meshextraction \
  --benchmarks build/benchmark/MeshExtractionBenchmarks --out "${1:-results/labels}"

#!/usr/bin/env bash
# Label images side by side with VTK's vtkSurfaceNets3D and vtkDiscreteFlyingEdges3D (PyPI,
# pinned in benchmark/peers/requirements.txt, in a venv under build/): quality, accuracy,
# validity and filter time (benchmark/peers/compare-labels.py). Usage: compare-labels.sh [OUTDIR [OPTIONS]]
# (OPTIONS go to compare-labels.py, e.g. --only-many-labels).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/examples/meshextraction ] && [ -x build/benchmark/MeshExtractionBenchmarks ] || bash scripts/build.sh
venv=build/peers-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet -r benchmark/peers/requirements.txt
fi
out="${1:-results/labels}"
# The head CT's soft tissue and bone as labels, where the Debian data is installed;
ct=()
if bash scripts/prepare-data.sh "$out/data" > /dev/null 2>&1 && [ -f "$out/data/cranium.nhdr" ]; then
  ct=(--head-ct "$out/data/cranium.nhdr")
fi
# The AAL atlas of mricron-data (116 labels), a real label map.
atlas=/usr/share/mricron/templates/aal.nii.gz
[ -f "$atlas" ] && ct+=(--atlas "$atlas")
"$venv/bin/python" benchmark/peers/compare-labels.py --meshextraction build/examples/meshextraction \
  --benchmarks build/benchmark/MeshExtractionBenchmarks --out "$out" "${ct[@]}" "${@:2}"

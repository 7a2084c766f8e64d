#!/usr/bin/env bash
# Installs what MeshExtraction needs on Debian bookworm, from Debian's archive only:
# ITK 5.2.1, VTK 9.1 (for the comparison tool), GoogleTest, Google Benchmark, the
# build tools, and the real data the main job uses: the head CT of invesalius-examples
# and the Colin27 T1 MRI of mricron-data; for meshextraction-cohort (tools/cohort/),
# Dask's distributed scheduler for /usr/bin/python3, and GNU time (per-task memory).
# With --wheel, also what building ITK's Python wrapping and the wheel needs (scripts/
# build-itk.sh, scripts/build-wheel.sh): castxml, oneTBB (PyPI's itk threads with TBB) and
# python3-venv; their Python tools come from PyPI into a venv (scripts/lib/python-tools.sh).
set -euo pipefail
packages=(
  build-essential cmake ninja-build ccache
  libinsighttoolkit5-dev libvtk9-dev libgtest-dev libbenchmark-dev
  python3 invesalius-examples mricron-data
  python3-distributed time
  xvfb xauth hdf5-tools
  clang-14 libfuzzer-14-dev libclang-rt-14-dev
)
if [ "${1:-}" = "--wheel" ]; then
  packages+=(castxml libtbb-dev python3-venv git)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: everything is installed"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo=sudo
fi
echo "install-dependencies: installing ${missing[*]}"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"

#!/usr/bin/env bash
# Installs what MeshExtraction needs on Debian bookworm, from Debian's archive only:
# ITK 5.2.1, VTK 9.1 (for the comparison tool), GoogleTest, Google Benchmark, the
# build tools, and the real data the main job uses: the head CT of invesalius-examples
# and the Colin27 T1 MRI of mricron-data; for meshextraction-cohort (tools/cohort/),
# Dask's distributed scheduler for /usr/bin/python3, and GNU time (per-task memory).
set -euo pipefail
packages=(
  build-essential cmake ninja-build ccache
  libinsighttoolkit5-dev libvtk9-dev libgtest-dev libbenchmark-dev
  python3 invesalius-examples mricron-data
  python3-distributed time
  xvfb xauth hdf5-tools
  clang-14 libfuzzer-14-dev libclang-rt-14-dev
)
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

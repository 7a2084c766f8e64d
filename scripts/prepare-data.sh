#!/usr/bin/env bash
# Unpacks the real CT of Debian's invesalius-examples package into DIR (default
# ./data) as a NRRD the module reads: cranium.nhdr + cranium.raw (int16 HU,
# 256x256x108, 0.957x0.957x1.5 mm). The package must be installed
# (apt-get install invesalius-examples); nothing here is committed to the project.
set -euo pipefail
dir=${1:-data}
archive=/usr/share/doc/invesalius-examples/examples/Cranium.inv3
mkdir -p "$dir"
if [ ! -f "$archive" ]; then
  echo "prepare-data: $archive not found: install the invesalius-examples package" >&2
  exit 1
fi
if [ ! -f "$dir/cranium.raw" ]; then
  tmp=$(mktemp -d)
  tar xzf "$archive" -C "$tmp"
  matrix=$(find "$tmp" -name matrix.dat | head -n 1)
  mv "$matrix" "$dir/cranium.raw"
  bone=$(find "$tmp" -name surface_0.vtp | head -n 1)
  [ -n "$bone" ] && mv "$bone" "$dir/cranium-invesalius-bone.vtp"
  rm -rf "$tmp"
fi
# main.plist of the archive: dtype int16, shape (108, 256, 256), spacing 0.957 0.957 1.5.
cat > "$dir/cranium.nhdr" <<'NRRD'
NRRD0004
# InVesalius example "Cranium" (ProMED CT 0051), from Debian's invesalius-examples
type: short
dimension: 3
space: left-posterior-superior
sizes: 256 256 108
space directions: (0.9570312,0,0) (0,0.9570312,0) (0,0,1.5)
space origin: (0,0,0)
encoding: raw
endian: little
data file: cranium.raw
NRRD
echo "prepare-data: $dir/cranium.nhdr"

# The small head CT of ../shared/data/ct_headsq, when that folder is next to the project
# (it is not part of it): its header gives both 'space:' and 'spacings:', which ITK's NRRD
# reader refuses ("Error interpreting nrrd spacing"), so write a copy without the space
# line that points at the raw file where it is.
shared=${MESHEXTRACTION_SHARED_DATA:-$(cd "$(dirname "$0")/.." && pwd)/../shared/data}
if [ -f "$shared/ct_headsq/headsq_quarter.nhdr" ]; then
  raw=$(cd "$shared/ct_headsq" && pwd)/headsq_quarter.raw
  grep -v '^space:' "$shared/ct_headsq/headsq_quarter.nhdr" | sed "s|^data file: .*|data file: $raw|" > "$dir/headsq.nhdr"
  echo "prepare-data: $dir/headsq.nhdr"
fi

#!/usr/bin/env bash
# Issue 32, case 11: every output is written whole or not at all. Under a file-size limit
# the JSON, CSV and SVG reports, images and renderings fail with exit 1 and a message,
# leave the file that was there unchanged, and leave no partial file behind.
# Usage: CheckWholeOutputs.sh MESHEXTRACTION OCTAHEDRON.obj WORKDIR
set -euo pipefail
tool=$1
mesh=$2
dir=$3
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"
fail() { echo "FAIL: $*" >&2; exit 1; }

# Good outputs first, of sizes above the limit below (1 block of 512 bytes).
"$tool" quality "$mesh" --json q.json --csv h.csv > /dev/null
"$tool" phantom sphere s.nrrd --size 32 --pixel-type float > /dev/null 2>&1
[ "$(stat -c %s q.json)" -gt 512 ] && [ "$(stat -c %s h.csv)" -gt 512 ] && [ "$(stat -c %s s.nrrd)" -gt 512 ] ||
  fail "the good outputs are too small for the test"
before=$(sha256sum q.json h.csv s.nrrd)

check() { # check NAME COMMAND...: exit 1, a message naming the file, nothing replaced or left
  local name=$1
  shift
  set +e
  out=$(sh -c 'ulimit -f 1 && exec "$@"' sh "$@" 2>&1)
  status=$?
  set -e
  [ "$status" -eq 1 ] || fail "$name: exit status $status, expected 1: $out"
  echo "$out" | grep -q "cannot write" || fail "$name: no 'cannot write' in: $out"
  [ "$(sha256sum q.json h.csv s.nrrd)" = "$before" ] || fail "$name: an existing output changed"
  if ls -a | grep -q partial; then fail "$name: a partial file is left: $(ls -a)"; fi
  echo "ok: $name"
}
check "quality --json" "$tool" quality "$mesh" --json q.json
check "quality --csv" "$tool" quality "$mesh" --csv h.csv
check "phantom image" "$tool" phantom sphere s.nrrd --size 32 --pixel-type float

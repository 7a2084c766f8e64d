#!/usr/bin/env bash
# Issue 48, cases 2-4: a run that fails leaves what was there as it was. A shape model
# whose write fails under a file-size limit: exit 1 with a message, no crash, the old
# model unchanged. A report that fails (a NaN mesh among the inputs, a missing
# --include): the old report unchanged, no staging folder or partial file left.
# Usage: CheckOutputsKept.sh MESHEXTRACTION OCTAHEDRON.obj WORKDIR
set -euo pipefail
tool=$1
mesh=$2
dir=$3
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"
fail() { echo "FAIL: $*" >&2; exit 1; }
leftovers() { find . -name '*partial*' | head -5; }

# The model: two ellipsoids, then the same build under a 1 KB limit.
"$tool" extract --phantom ellipsoid a.ply --size 16 > /dev/null 2>&1
"$tool" extract --phantom ellipsoid b.ply --size 16 --spacing 1.2x1x1 > /dev/null 2>&1
"$tool" shape-model build a.ply b.ply --output model.h5 > /dev/null 2>&1
[ "$(stat -c %s model.h5)" -gt 1024 ] || fail "the model is too small for the test"
model=$(sha256sum model.h5)
set +e
out=$(sh -c 'ulimit -f 2 && exec "$@"' sh "$tool" shape-model build a.ply b.ply --output model.h5 2>&1)
status=$?
set -e
[ "$status" -eq 1 ] || fail "model under a size limit: exit status $status, expected 1: $out"
echo "$out" | grep -q "cannot write 'model.h5'" || fail "model: no 'cannot write' in: $out"
echo "$out" | grep -q "model written" && fail "model: says 'model written' although the write failed: $out"
[ "$(sha256sum model.h5)" = "$model" ] || fail "the old model was replaced"
[ -z "$(leftovers)" ] || fail "model: left $(leftovers)"
echo "ok: a failed model write keeps the old model"

# The report.
"$tool" report report "$mesh" > /dev/null 2>&1
[ -f report/index.html ] && [ -f report/mesh-1.png ] || fail "the first report is incomplete: $(ls report)"
page=$(cd report && sha256sum ./*)
printf 'v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n' > nan.obj
for case in nan include; do
  set +e
  if [ $case = nan ]; then
    out=$("$tool" report report "$mesh" nan.obj 2>&1)
  else
    out=$("$tool" report report "$mesh" --include no-such-file.html 2>&1)
  fi
  status=$?
  set -e
  [ "$status" -eq 1 ] || fail "report ($case): exit status $status, expected 1: $out"
  [ "$(cd report && sha256sum ./*)" = "$page" ] || fail "report ($case): the old report changed"
  [ -z "$(leftovers)" ] || fail "report ($case): left $(leftovers)"
  echo "ok: a failed report ($case) keeps the old one"
done

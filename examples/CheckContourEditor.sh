#!/bin/bash
# The contours.editor_replay test: replays a recorded interaction with
# meshextraction-contours under xvfb-run, then checks the model's state after it, the
# saved model and mesh (a valid closed surface), and the screenshot against a stored one.
# Exit 77 (skipped) where no X server can be started.
# Usage: CheckContourEditor.sh EDITOR CLI EVENTS BASELINE_PNG WORKDIR
set -u
editor=$1
cli=$2
events=$3
baseline=$4
work=$5
if ! command -v xvfb-run > /dev/null; then
  echo "SKIPPED: xvfb-run not found (Debian package xvfb): the editor renders only through X"
  exit 77
fi
if ! xvfb-run -a true > /dev/null 2>&1; then
  echo "SKIPPED: xvfb-run cannot start an X server here"
  exit 77
fi
mkdir -p "$work" && cd "$work" || exit 1
rm -f model.json mesh.vtk replay.png
"$cli" phantom ellipsoid phantom.nrrd --size 48x48x48 --image-mode step > phantom.log 2>&1 || {
  cat phantom.log
  exit 1
}
output=$(xvfb-run -a -s "-screen 0 1024x768x24" "$editor" phantom.nrrd --replay "$events" --window-size 600 \
  --screenshot replay.png --baseline "$baseline" --threshold 10 --output-model model.json --output-mesh mesh.vtk 2>&1)
status=$?
echo "$output"
fail() {
  echo "FAILED: $1"
  exit 1
}
[ $status -eq 0 ] || fail "the editor exited with status $status"
expected='state: {"contours": 4, "control_points": 10, "undo": 3, "invariants": "ok"'
grep -qF "$expected" <<< "$output" || fail "the model's state after the replay is not $expected"
grep -qF "undo: " <<< "$output" || fail "the undo did not run"
[ -s model.json ] && [ -s mesh.vtk ] || fail "the model and the mesh were not saved"
"$cli" quality mesh.vtk > quality.log 2>&1 || fail "cannot measure the saved mesh: $(cat quality.log)"
grep -q "valid closed surface: yes" quality.log || fail "the saved mesh is not a valid closed surface"
echo "ok: state, saved model and mesh (a valid closed surface), screenshot within the threshold"

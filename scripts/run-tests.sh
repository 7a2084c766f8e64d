#!/usr/bin/env bash
# The test command: installs the dependencies, builds, and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dependencies.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
# A short, deterministic run of the libFuzzer harnesses (mesh-file readers, SurfaceNets on
# small volumes) in build-fuzz/; scripts/run-fuzzers.sh --seconds S runs them longer.
bash scripts/run-fuzzers.sh --smoke build-fuzz
# The wheel and the Python tests, where a wrapped ITK tree has been made (scripts/build-itk.sh;
# building one takes most of an hour, so the test command does not).
source scripts/lib/python-tools.sh
itk_python_tree="$(meshextraction_wheel_itk_dir)"
if grep -qs '^ITK_WRAP_PYTHON:BOOL=ON' "$itk_python_tree/CMakeCache.txt"; then
  bash scripts/install-dependencies.sh --wheel
  bash scripts/build-wheel.sh "$itk_python_tree"
  bash scripts/run-python-tests.sh
else
  echo "run-tests: Python tests skipped: no wrapped ITK tree at $itk_python_tree (scripts/build-itk.sh makes one; MESHEXTRACTION_ITK_PYTHON_DIR names another)"
fi

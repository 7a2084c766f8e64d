#!/usr/bin/env bash
# Runs the module's Python tests (wrapping/test) as a user has the module after
# `pip install`: a new venv, PyPI's itk 5.4.7, the wheel from dist/ (scripts/build-
# wheel.sh) and pytest; no PYTHONPATH into a build tree, no environment variable.
#
#   scripts/run-python-tests.sh [PYTEST_ARGUMENTS...]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(dirname "$here")"
# shellcheck source=lib/python-tools.sh
source "$here/lib/python-tools.sh"

shopt -s nullglob
wheels=("$repo"/dist/itk_meshextraction-*.whl)
if [ ${#wheels[@]} -ne 1 ]; then
  echo "run-python-tests: expected one itk_meshextraction wheel in dist/, found ${#wheels[@]} (scripts/build-wheel.sh makes it)" >&2
  exit 2
fi
python="$(meshextraction_base_python)"
venv="$(mktemp -d "${TMPDIR:-/tmp}/meshextraction-python-tests.XXXXXX")"
trap 'rm -rf "$venv"' EXIT
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install -q --upgrade pip
"$venv/bin/python" -m pip install -q -r "$here/python/python-test-requirements.txt" "${wheels[0]}"
"$venv/bin/python" -c "import itk; itk.SurfaceNetsImageToMeshFilter; print('itk', itk.Version.GetITKVersion(), '+', '$(basename "${wheels[0]}")')"
# From a folder outside the repository, so that nothing but the installed packages is imported.
cd "$venv"
env -u PYTHONPATH "$venv/bin/python" -m pytest -p no:cacheprovider "$repo/wrapping/test" "$@"

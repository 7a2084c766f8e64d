#!/usr/bin/env bash
# Builds the itk-meshextraction wheel into dist/ against a wrapped ITK tree made by
# scripts/build-itk.sh (ITK v5.4.7), with scikit-build-core, as ITK's module-wheel
# scripts make remote-module wheels:
#
#   scripts/build-wheel.sh ITK_BUILD_DIR
#
# The wheel holds the module's Python extension (the module and the ITK code it uses
# linked statically, Python's limited API: cp311-abi3), its generated Python modules and
# itk.meshextraction; no itk/__init__.py and no ITK shared library: it installs beside
# PyPI's itk 5.4. auditwheel then bundles the one shared library it needs beyond the
# manylinux set (oneTBB) and gives it the manylinux tag this machine's glibc allows.
# The CMake build tree is kept in build-wheel/ so that a rebuild takes minutes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(dirname "$here")"
# shellcheck source=lib/python-tools.sh
source "$here/lib/python-tools.sh"

if [ $# -ne 1 ] || [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
itk_build="$(realpath "$1")"
if ! grep -qs '^ITK_WRAP_PYTHON:BOOL=ON' "$itk_build/CMakeCache.txt"; then
  echo "build-wheel: $itk_build is not an ITK build tree with Python wrapping (make one with scripts/build-itk.sh)" >&2
  exit 2
fi
tools="$(meshextraction_venv wheel-tools "$here/python/wheel-build-requirements.txt")"
export PATH="$tools/bin:$PATH"
# The Python and castxml the ITK tree's wrapping was made with.
python="$(grep '^Python3_EXECUTABLE:' "$itk_build/CMakeCache.txt" | cut -d= -f2)"
castxml="$(grep '^CASTXML_EXECUTABLE:' "$itk_build/CMakeCache.txt" | cut -d= -f2)"
# The build tree is the checkout's own (build-wheel/, ignored by git); with ccache's base
# folder at the checkout, another clone of the same sources finds the compiled objects.
build_dir="$repo/build-wheel"
export CCACHE_BASEDIR="$repo"
raw="$build_dir/raw"
rm -rf "$raw"
mkdir -p "$raw" "$repo/dist"

start=$(date +%s)
define() { echo "--config-setting=cmake.define.$1"; }
"$tools/bin/python" -m build --wheel --no-isolation --skip-dependency-check --outdir "$raw" \
  --config-setting=build-dir="$build_dir/{wheel_tag}" \
  --config-setting=wheel.py-api=cp311 \
  --config-setting=cmake.build-type=Release \
  --config-setting=cmake.args=-GNinja \
  "$(define ITK_DIR:PATH="$itk_build")" \
  "$(define WRAP_ITK_INSTALL_COMPONENT_IDENTIFIER:STRING=PythonWheel)" \
  "$(define PY_SITE_PACKAGES_PATH:PATH=.)" \
  "$(define CMAKE_INSTALL_LIBDIR:STRING=lib)" \
  "$(define BUILD_TESTING:BOOL=OFF)" \
  "$(define Python3_EXECUTABLE:FILEPATH="$python")" \
  "$(define ITK_USE_SYSTEM_SWIG:BOOL=ON)" \
  "$(define SWIG_EXECUTABLE:FILEPATH="$tools/bin/swig")" \
  "$(define ITK_USE_SYSTEM_CASTXML:BOOL=ON)" \
  "$(define CASTXML_EXECUTABLE:FILEPATH="$castxml")" \
  "$(define ITK_USE_KWSTYLE:BOOL=OFF)" \
  "$(define CMAKE_CXX_COMPILER_LAUNCHER:STRING=ccache)" \
  "$repo" > "$build_dir/build.log" 2>&1 || {
  tail -40 "$build_dir/build.log" >&2
  echo "build-wheel: the build failed (log: $build_dir/build.log)" >&2
  exit 1
}
wheel="$(ls "$raw"/itk_meshextraction-*.whl)"

# What the wheel must not hold: the itk package's own __init__.py, or a link to an ITK
# shared library (ITK comes from PyPI's itk; the module's extension has it built in).
"$tools/bin/python" - "$wheel" <<'EOF'
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
bad = [n for n in names if n in ("itk/__init__.py",) or n.startswith("itk/support/")]
if bad:
    sys.exit("build-wheel: the wheel holds files of PyPI's itk: %s" % bad)
if not any(n.startswith("itk/_MeshExtractionPython") for n in names):
    sys.exit("build-wheel: the wheel has no itk/_MeshExtractionPython extension")
EOF
unpacked="$build_dir/unpacked"
rm -rf "$unpacked" && mkdir -p "$unpacked"
(cd "$unpacked" && "$tools/bin/python" -m zipfile -e "$wheel" .)
if readelf -d "$unpacked"/itk/_MeshExtractionPython*.so | grep -E 'NEEDED.*lib(ITK|itk)'; then
  echo "build-wheel: the extension links an ITK shared library" >&2
  exit 1
fi

rm -f "$repo"/dist/itk_meshextraction-*.whl
auditwheel repair --wheel-dir "$repo/dist" "$wheel" > "$build_dir/auditwheel.log" 2>&1 || {
  cat "$build_dir/auditwheel.log" >&2
  exit 1
}
echo "build-wheel: $(ls "$repo"/dist/itk_meshextraction-*.whl) in $(($(date +%s) - start)) s"

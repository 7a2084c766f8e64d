#!/usr/bin/env bash
# Configures and builds an ITK tree for MeshExtraction from a checkout of an ITK release
# tag (v5.4.7 for the wheel; v5.4.7 or v6.0b02 for the C++ checks):
#
#   scripts/build-itk.sh [--no-wrapping] ITK_SOURCE_DIR BUILD_DIR
#
# With wrapping (the default) the tree has the settings of PyPI's itk 5.4.7 wheels that
# matter for binary compatibility: static libraries (so the module's wrapping shares
# ITK's singletons with PyPI's itk through _ITKCommonPython), TBB as the default
# threader, the Python limited API (abi3, CPython 3.11), SWIG 4.3.0, wrapped types a
# subset of PyPI's (unsigned char, unsigned short, short, float, double; 2-D and 3-D).
# Only the ITK modules MeshExtraction, its tests and its command-line tool use are
# enabled, and of the wrapping only what the module's wrapping reads is built (each
# dependency's libraries and its SWIG metadata), not ITK's whole Python package.
# --no-wrapping builds the same modules without the Python wrapping (for the C++ builds).
#
# BUILD_DIR must be outside this repository; a kept BUILD_DIR (and ccache) makes a rerun
# take minutes. The tools come from PyPI into a venv (scripts/python/wheel-build-
# requirements.txt); castxml and ccache from Debian (scripts/install-dependencies.sh --wheel).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(dirname "$here")"
# shellcheck source=lib/python-tools.sh
source "$here/lib/python-tools.sh"

usage() {
  sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
wrapping=ON
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --no-wrapping) wrapping=OFF ;;
    -h | --help) usage ;;
    -*) echo "build-itk: unknown option $1" >&2; usage ;;
    *) args+=("$1") ;;
  esac
  shift
done
[ ${#args[@]} -eq 2 ] || usage
itk_source="$(realpath "${args[0]}")"
mkdir -p "${args[1]}"
itk_build="$(realpath "${args[1]}")"
if [ ! -f "$itk_source/Modules/Core/Common/itk-module.cmake" ]; then
  echo "build-itk: $itk_source is not an ITK source tree (no Modules/Core/Common/itk-module.cmake)" >&2
  exit 2
fi
case "$itk_build/" in
  "$repo/"*) echo "build-itk: BUILD_DIR $itk_build is inside the repository; put it outside" >&2; exit 2 ;;
esac
for tool in ccache $([ "$wrapping" = ON ] && echo castxml); do
  command -v "$tool" > /dev/null || {
    echo "build-itk: $tool is missing; run scripts/install-dependencies.sh --wheel" >&2
    exit 2
  }
done

tools="$(meshextraction_venv wheel-tools "$here/python/wheel-build-requirements.txt")"
export PATH="$tools/bin:$PATH"

# The ITK modules: the module's, its tests' and its command-line tool's (one list each,
# in itk-module.cmake and examples/ITKComponents.cmake).
mapfile -t lists < <(cmake -P "$repo/CMake/MeshExtractionPrintITKModules.cmake")
read -r -a depends <<< "${lists[0]#DEPENDS }"
module_flags=()
for m in ${lists[0]#DEPENDS } ${lists[1]#TEST } ${lists[2]#EXAMPLES }; do
  module_flags+=("-DModule_$m:BOOL=ON")
done

wrap_flags=(-DITK_WRAP_PYTHON:BOOL=OFF)
if [ "$wrapping" = ON ]; then
  python="$(meshextraction_base_python)"
  wrap_flags=(
    -DITK_WRAP_PYTHON:BOOL=ON
    -DITK_USE_PYTHON_LIMITED_API:BOOL=ON
    -DPython3_EXECUTABLE:FILEPATH="$python"
    -DITK_WRAP_unsigned_char:BOOL=ON
    -DITK_WRAP_unsigned_short:BOOL=ON
    -DITK_WRAP_signed_short:BOOL=ON
    -DITK_WRAP_float:BOOL=ON
    -DITK_WRAP_double:BOOL=ON
    # 3-D alone fails in castxml on ITKImageGradient; PyPI's wheels wrap 2;3;4.
    "-DITK_WRAP_IMAGE_DIMS:STRING=2;3"
    "-DITK_WRAP_VECTOR_COMPONENTS:STRING=2;3;4"
    -DITK_USE_SYSTEM_SWIG:BOOL=ON
    -DSWIG_EXECUTABLE:FILEPATH="$tools/bin/swig"
    -DITK_USE_SYSTEM_CASTXML:BOOL=ON
    -DCASTXML_EXECUTABLE:FILEPATH="$(command -v castxml)"
    -DITK_WRAP_DOC:BOOL=OFF
  )
fi

start=$(date +%s)
# ITK's configure rewrites the castxml flags file even when its contents are the same,
# and every castxml run of the wrapping depends on it: keep its time when nothing
# changed, or a rerun would remake all the wrapping metadata (a quarter of an hour).
castxml_inc="$itk_build/Wrapping/castxml_inputs/.castxml.inc"
[ -f "$castxml_inc" ] && cp -p "$castxml_inc" "$castxml_inc.before"
cmake -S "$itk_source" -B "$itk_build" -G Ninja \
  -DCMAKE_MAKE_PROGRAM:FILEPATH="$tools/bin/ninja" \
  -DCMAKE_BUILD_TYPE:STRING=Release \
  -DCMAKE_C_COMPILER_LAUNCHER:STRING=ccache \
  -DCMAKE_CXX_COMPILER_LAUNCHER:STRING=ccache \
  -DBUILD_SHARED_LIBS:BOOL=OFF \
  -DBUILD_TESTING:BOOL=OFF \
  -DBUILD_EXAMPLES:BOOL=OFF \
  -DITK_BUILD_DEFAULT_MODULES:BOOL=OFF \
  -DModule_ITKTBB:BOOL=ON \
  "${module_flags[@]}" \
  "${wrap_flags[@]}" \
  > "$itk_build/build-itk-configure.log"
if [ -f "$castxml_inc.before" ]; then
  if cmp -s "$castxml_inc" "$castxml_inc.before"; then touch -r "$castxml_inc.before" "$castxml_inc"; fi
  rm -f "$castxml_inc.before"
fi
echo "build-itk: configured $itk_build (log: build-itk-configure.log)"

# What the module builds against: every library and tool of the enabled modules and,
# with wrapping, the SWIG metadata of the module's wrapped dependencies (their
# <Module>Swig targets bring the metadata of their own dependencies).
all_targets="$(ninja -C "$itk_build" -t targets all | cut -d: -f1)"
targets=()
while read -r t; do targets+=("$t"); done < <(grep -E '^(lib/lib[^/]+\.(a|so)|bin/[^/.]+)$' <<< "$all_targets")
if [ "$wrapping" = ON ]; then
  for m in "${depends[@]}" ITKPyBase; do
    if grep -qx "${m}Swig" <<< "$all_targets"; then targets+=("${m}Swig"); fi
  done
fi
echo "build-itk: building ${#targets[@]} targets"
cmake --build "$itk_build" --target "${targets[@]}"
echo "build-itk: $itk_build built in $(($(date +%s) - start)) s (wrapping $wrapping)"

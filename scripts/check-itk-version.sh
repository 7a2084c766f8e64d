#!/usr/bin/env bash
# Builds and tests MeshExtraction against an ITK release (v5.4.7, v6.0b02, ...) both ways
# ITK users build remote modules, with every C++ test and no warning in the module's
# code under ITK's own warning flags:
#
#   scripts/check-itk-version.sh ITK_SOURCE_DIR WORK_DIR
#
#   WORK_DIR/itk       ITK made by scripts/build-itk.sh --no-wrapping (kept between runs)
#   WORK_DIR/external  the module as an external module (ITK_DIR=WORK_DIR/itk): library,
#                      tests, command-line tool and benchmarks; ctest runs every test
#   WORK_DIR/remote    ITK configured with the module in Modules/Remote/MeshExtraction
#                      (a link made for the run, removed after it) and
#                      Module_MeshExtraction=ON, BUILD_TESTING=ON; the module's library
#                      and test driver built and run (ITK's own tests are not built)
#
# WORK_DIR must be outside this repository. Logs: WORK_DIR/*.log.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(dirname "$here")"
# shellcheck source=lib/python-tools.sh
source "$here/lib/python-tools.sh"

if [ $# -ne 2 ]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
itk_source="$(realpath "$1")"
mkdir -p "$2"
work="$(realpath "$2")"
case "$work/" in
  "$repo/"*) echo "check-itk-version: WORK_DIR $work is inside the repository; put it outside" >&2; exit 2 ;;
esac
tools="$(meshextraction_venv wheel-tools "$here/python/wheel-build-requirements.txt")"
export PATH="$tools/bin:$PATH"
# Paths relative to each build folder, so that the remote tree (a sibling of WORK_DIR/itk)
# finds ITK's objects in ccache.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-/}"
version="$(sed -nE 's/^set\(ITK_VERSION_(MAJOR|MINOR|PATCH) "?([0-9]+)"?\)/\2/p' "$itk_source/CMake/itkVersion.cmake" | paste -sd.)"
echo "check-itk-version: ITK $version from $itk_source"

# Warnings in the module's own files (ITK's and third-party headers are ITK's business).
module_warnings() {
  # Paths may be relative (CCACHE_BASEDIR): ITK's files are those under a Modules/ folder
  # other than Modules/Remote/MeshExtraction.
  grep -E ": warning:" "$1" | grep -E "Modules/Remote/MeshExtraction/|^[^:]*/(src|include|examples|test|benchmark|fuzz|tools)/" |
    grep -vP "^[^:]*Modules/(?!Remote/MeshExtraction/)" || true
}
report() {
  local log="$1" what="$2"
  local warnings
  warnings="$(module_warnings "$log" | sort -u)"
  if [ -n "$warnings" ]; then
    echo "$warnings" | head -20
    echo "check-itk-version: $what: $(echo "$warnings" | wc -l) warnings in the module's code (log: $log)" >&2
    return 1
  fi
}

# 1. ITK without wrapping.
bash "$here/build-itk.sh" --no-wrapping "$itk_source" "$work/itk" > "$work/itk.log" 2>&1 || {
  tail -30 "$work/itk.log" >&2
  exit 1
}
tail -1 "$work/itk.log"

# 2. External module.
start=$(date +%s)
cmake -S "$repo" -B "$work/external" -G Ninja -DCMAKE_BUILD_TYPE=Release -DITK_DIR="$work/itk" \
  -DBUILD_TESTING=ON -DITK_USE_KWSTYLE=OFF -DITK_USE_CLANG_FORMAT=OFF -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  > "$work/external.log" 2>&1
cmake --build "$work/external" >> "$work/external.log" 2>&1 || {
  grep -E "error|Error" "$work/external.log" | head -30 >&2
  exit 1
}
[ -x "$work/external/bin/meshextraction" ] || {
  echo "check-itk-version: the external build made no command-line tool" >&2
  exit 1
}
report "$work/external.log" external
ctest --test-dir "$work/external" -j "$(nproc)" > "$work/external-ctest.log" 2>&1 || {
  grep -E "Failed|\*\*\*" "$work/external-ctest.log" | head -30 >&2
  echo "check-itk-version: external module tests failed (log: $work/external-ctest.log)" >&2
  exit 1
}
echo "check-itk-version: external module: $(grep -E 'tests passed' "$work/external-ctest.log") ($(($(date +%s) - start)) s)"

# 3. Remote module inside ITK's source tree.
start=$(date +%s)
link="$itk_source/Modules/Remote/MeshExtraction"
if [ -e "$link" ] && [ ! -L "$link" ]; then
  echo "check-itk-version: $link exists and is not a link; remove it" >&2
  exit 2
fi
ln -sfn "$repo" "$link"
trap 'rm -f "$link"' EXIT
mapfile -t lists < <(cmake -P "$repo/CMake/MeshExtractionPrintITKModules.cmake")
module_flags=()
for m in ${lists[0]#DEPENDS } ${lists[1]#TEST }; do module_flags+=("-DModule_$m:BOOL=ON"); done
cmake -S "$itk_source" -B "$work/remote" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF \
  -DBUILD_TESTING=ON -DBUILD_EXAMPLES=OFF -DITK_BUILD_DEFAULT_MODULES=OFF -DModule_ITKTBB=ON \
  -DModule_MeshExtraction=ON "${module_flags[@]}" -DITK_WRAP_PYTHON=OFF -DITK_USE_CLANG_FORMAT=OFF \
  -DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache > "$work/remote.log" 2>&1
cmake --build "$work/remote" --target MeshExtraction-all MeshExtractionGTestDriver >> "$work/remote.log" 2>&1 || {
  grep -E "error|Error" "$work/remote.log" | head -30 >&2
  exit 1
}
report "$work/remote.log" remote
# ITK's own tests are not built: run the module's GoogleTest driver and its other tests.
driver="$(find "$work/remote" -name MeshExtractionGTestDriver -type f -perm -u+x | head -1)"
"$driver" --gtest_brief=1 > "$work/remote-gtest.log" 2>&1 || {
  grep -E "FAILED" "$work/remote-gtest.log" | head -30 >&2
  echo "check-itk-version: remote module tests failed (log: $work/remote-gtest.log)" >&2
  exit 1
}
ctest --test-dir "$work/remote" -R '^MeshExtractionWrapping' > "$work/remote-ctest.log" 2>&1 || {
  echo "check-itk-version: remote module wrapping checks failed (log: $work/remote-ctest.log)" >&2
  exit 1
}
echo "check-itk-version: remote module: $(grep -E '^\[  PASSED  \]' "$work/remote-gtest.log"), $(grep -E 'tests passed' "$work/remote-ctest.log") ($(($(date +%s) - start)) s)"

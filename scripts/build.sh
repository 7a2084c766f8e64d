#!/usr/bin/env bash
# Configures and builds MeshExtraction in ./build (Release) against the installed ITK.
# With ccache (installed by install-dependencies.sh) a rebuild, or a build in a fresh
# clone of the same sources, compiles only what changed: its base folder is the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache > /dev/null; then
  export CCACHE_BASEDIR="$PWD"
  # The test driver's sources use a precompiled header (CMake passes it with -include),
  # which ccache caches only with this sloppiness.
  export CCACHE_SLOPPINESS="pch_defines,time_macros,include_file_mtime,include_file_ctime"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
cmake --build build -j "$(nproc)"

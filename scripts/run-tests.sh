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

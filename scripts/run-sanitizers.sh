#!/usr/bin/env bash
# Builds the module with AddressSanitizer and UndefinedBehaviorSanitizer (g++) in
# build-sanitizers/ and runs every test under them: a memory error or undefined behaviour
# anywhere the tests reach ends that test with the sanitizer's report.
#
#   bash scripts/run-sanitizers.sh [BUILD_DIR] [CTEST_ARGS...]   e.g. -R 'SurfaceNets|cli\.'
#
# Leak detection is off: ITK keeps singletons (object factories, the global default
# thread pool) alive to the end of the process on purpose, and LeakSanitizer reports them.
# The sanitized build takes several times the normal build's time; it is not part of CI.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-sanitizers}
shift || true
# Every finding ends the test (halt_on_error below); pointer-overflow is compiled
# recoverable only so that scripts/ubsan-suppressions.txt can name ITK's own (UBSan
# cannot suppress a check compiled unrecoverable).
flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -fsanitize-recover=pointer-overflow"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build "$build" -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
# ITK 5.2.1's own undefined behaviour (not this module's) is listed, with the reason, in
# scripts/ubsan-suppressions.txt.
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$PWD/scripts/ubsan-suppressions.txt
ctest --test-dir "$build" -j "$(nproc)" --output-on-failure "$@"

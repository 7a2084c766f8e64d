#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) with clang-14, AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz/, and runs each on a seed corpus:
#   MeshFileFuzzer    the mesh-file readers (VTK legacy, VTP, PLY, STL, OBJ, OFF) and the
#                     checks before a QuadEdgeMesh; a refusal is fine, a crash is not
#   ExtractionFuzzer  SurfaceNets on small volumes, and every label of small label maps in
#                     one pass; every emitted mesh (each label's surface) must be valid
#   CommandLineFuzzer the command-line tool's commands with fuzzed arguments: a refusal
#                     (exit 2) or a failure naming the file (exit 1) is fine, any other
#                     exception, a crash or a hang is not
#
#   bash scripts/run-fuzzers.sh [--smoke | --runs N | --seconds S] [BUILD_DIR]
#
# --seconds S per fuzzer (default 60), --runs N inputs per fuzzer, or --smoke, the short
# deterministic run of the test command (seed 1: 20,000 mesh files, 300 volumes, 1,000
# command lines). Findings
# are written to BUILD_DIR/findings/ and end the script with status 1.
# Needs Debian's clang-14, libfuzzer-14-dev and libclang-rt-14-dev.
set -euo pipefail
cd "$(dirname "$0")/.."
limit=(-max_total_time=60)
smoke=0
build=build-fuzz
while [ $# -gt 0 ]; do
  case $1 in
    --smoke) smoke=1; shift ;;
    --runs) limit=(-runs="$2" -seed=1); shift 2 ;;
    --seconds) limit=(-max_total_time="$2"); shift 2 ;;
    *) build=$1; shift ;;
  esac
done
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"
cxxflags="$flags -include $PWD/fuzz/ItkCompilerDetectionForClang.h -Wno-builtin-macro-redefined"
# ccache, with its base folder at the checkout, as scripts/build.sh uses it.
launcher=()
if command -v ccache > /dev/null; then
  export CCACHE_BASEDIR="$PWD"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DMESHEXTRACTION_BUILD_FUZZERS=ON -DBUILD_TESTING=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$cxxflags" > "$build-configure.log" 2>&1 ||
  { cat "$build-configure.log"; exit 1; }
mv "$build-configure.log" "$build/configure.log"
cmake --build "$build" -j "$(nproc)" --target MeshFileFuzzer ExtractionFuzzer CommandLineFuzzer

# Seeds: the test meshes in each format (the first byte chooses the reader), and a few
# small volumes; the corpus grows in BUILD_DIR/corpus/ from run to run.
# Absolute paths: CommandLineFuzzer works in a scratch directory of its own.
build=$(cd "$build" && pwd)
corpus=$build/corpus
mkdir -p "$corpus/mesh" "$corpus/extraction" "$corpus/commandline" "$build/findings"
index=0
for extension in vtk vtp ply stl obj off; do
  for seed in test/Input/*."$extension"; do
    [ -f "$seed" ] || continue
    { printf "\\x$(printf %02x $index)"; cat "$seed"; } > "$corpus/mesh/seed-$extension-$(basename "$seed")"
  done
  index=$((index + 1))
done
tetrahedron_off='OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n'
tetrahedron_ply='ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n'
tetrahedron_stl='solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n'
printf "\x05$tetrahedron_off" > "$corpus/mesh/seed-tetrahedron-off"
printf "\x02$tetrahedron_ply" > "$corpus/mesh/seed-tetrahedron-ply"
printf "\x03$tetrahedron_stl" > "$corpus/mesh/seed-triangle-stl"
# Issue 48: a coordinate beyond float range (OBJ), faces of 0 to 2 vertices (OFF, PLY, VTK).
octahedron_faces='f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n'
printf "\x04v 1e40 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n$octahedron_faces" > "$corpus/mesh/seed-far-obj"
printf '\x05OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n2 0 1\n0\n' > "$corpus/mesh/seed-short-faces-off"
printf "\x02${tetrahedron_ply/3 1 2 3/2 1 2}" > "$corpus/mesh/seed-short-face-ply"
printf '\x00# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 6\n3 0 1 2\n1 0\n' > "$corpus/mesh/seed-short-polygon-vtk"
printf '\x04\x04\x04\x00\x80\x80\x80\x80\x80\x05\x05\x80\x80\x05\x05\x80' > "$corpus/extraction/seed-block"
printf '\x06\x06\x06\x12\x80\x7f\x80\x7f\x00\x80\x7f\x80' > "$corpus/extraction/seed-checker-hq"
# Label maps (bit 5 of the settings): 3 labels, and 4 labels unrelaxed.
printf '\x05\x05\x05\xa0\x00\x01\x02\x03\x01\x02\x00\x03\x02' > "$corpus/extraction/seed-labels"
printf '\x04\x04\x04\xe1\x01\x02\x01\x02\x03\x04\x00\x04\x03' > "$corpus/extraction/seed-labels-checker"
# Command lines: the first byte chooses the command (0 phantom, 1 extract, 2 improve,
# 3 refine, 4 quality, 5 report, 6 match, 7 shape-model), NUL bytes separate the arguments;
# the scratch directory holds m.obj, m.vtk and s.nrrd.
seed_command() { # seed_command NAME INDEX ARGS...
  local name=$1 index=$2
  shift 2
  { printf "\\x$(printf %02x "$index")"; printf '%s\0' "$@"; } > "$corpus/commandline/seed-$name"
}
seed_command phantom 0 sphere p.nrrd --size 12 --spacing 1x1x2
seed_command extract 1 s.nrrd e.vtk --iso 0 --inside below --quality high --rounds 2 --report
seed_command extract-phantom 1 --phantom torus t.ply --size 16 --label-sigma 1.5 --min-component-voxels 3
seed_command extract-labels 1 s.nrrd l.vtk --label-thresholds -1,1 --combined c.vtp --label-list 1,2
seed_command improve 2 m.obj i.stl --iterations 3
seed_command refine 3 s.nrrd m.vtk r.vtk --max-deviation 2 --cycles 1 --csv r.csv
seed_command quality 4 m.obj m.vtk --json q.json --csv q.csv --phantom sphere --image s.nrrd
seed_command report 5 rep m.obj --title x
seed_command match 6 s.nrrd s.nrrd --fixed-landmarks a.json --moving-landmarks b.json
seed_command shape-model 7 m.obj m.obj --output x.h5
seed_command renew 7 renew m.obj st.json --output r.ply --json r.json
seed_command renew-rotation 7 renew m.obj st-rotation.json --output r.ply --json r.json
seed_command renew-scale 7 renew m.obj st-scale.json st.json --output r.ply --json r.json
seed_command sample-broken-model 7 sample bad.h5 --output x.ply --coefficients=1,-2
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for fuzzer in MeshFileFuzzer ExtractionFuzzer CommandLineFuzzer; do
  dir=$corpus/mesh
  [ $fuzzer = ExtractionFuzzer ] && dir=$corpus/extraction
  [ $fuzzer = CommandLineFuzzer ] && dir=$corpus/commandline
  if [ $smoke = 1 ]; then
    runs=20000
    [ $fuzzer = ExtractionFuzzer ] && runs=300
    [ $fuzzer = CommandLineFuzzer ] && runs=1000
    limit=(-runs=$runs -seed=1)
  fi
  echo "== $fuzzer ${limit[*]}"
  if ! "$build/fuzz/$fuzzer" "${limit[@]}" -max_len=4096 -timeout=20 -rss_limit_mb=2048 \
    -artifact_prefix="$build/findings/$fuzzer-" "$dir" 2>&1 | tail -n 25; then
    status=1
  fi
done
if ls "$build"/findings/* > /dev/null 2>&1; then
  echo "run-fuzzers: findings in $build/findings/:"
  ls "$build"/findings/
  status=1
fi
exit $status

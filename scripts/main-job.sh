#!/usr/bin/env bash
# Runs the main job with an existing build (see run-main-job.sh). OUT defaults to ./results.
set -euo pipefail
out=${1:-results}
me=${MESHEXTRACTION:-build/examples/meshextraction}
compare=${MESHEXTRACTION_COMPARE:-build/examples/meshextraction-compare}
mkdir -p "$out"
log() { echo "== $*" >&2; }

# 1. Phantoms: a sphere distance map (128^3, radius 38.4 mm) and two overlapping spheres.
for shape in sphere two-spheres; do
  log "$shape: SNA, SNERT and high-quality SurfaceNets"
  "$me" extract --phantom "$shape" --size 128 --relaxation sna "$out/$shape-sna.vtk"
  "$me" extract --phantom "$shape" --size 128 "$out/$shape-snert.vtk"
  "$me" extract --phantom "$shape" --size 128 --quality high "$out/$shape-high.vtk"
  if [ -x "$compare" ]; then
    "$compare" --phantom "$shape" --size 128 --methods all --markdown "$out/comparison-$shape.md" \
      --csv "$out/comparison-$shape.csv" > "$out/comparison-$shape.txt"
  fi
  include=()
  [ -f "$out/comparison-$shape.md" ] && include=(--include "$out/comparison-$shape.md")
  "$me" report "$out/$shape" "$out/$shape-sna.vtk" "$out/$shape-snert.vtk" "$out/$shape-high.vtk" \
    --phantom "$shape" --size 128 --title "SurfaceNets on the $shape phantom (128^3)" "${include[@]}"
done

# 2. The real head CT (skull at 300 HU), when invesalius-examples is installed.
if bash scripts/prepare-data.sh "$out/data"; then
  log "head CT: bone surface at 300 HU"
  "$me" extract "$out/data/cranium.nhdr" --iso 300 "$out/cranium-snert.vtk"
  "$me" extract "$out/data/cranium.nhdr" --iso 300 --quality high "$out/cranium-high.vtk"
  if [ -x "$compare" ]; then
    "$compare" "$out/data/cranium.nhdr" --iso 300 --methods all --repeat 1 --write-meshes "$out/cranium-methods" \
      --markdown "$out/comparison-cranium.md" --csv "$out/comparison-cranium.csv" > "$out/comparison-cranium.txt"
  fi
  include=()
  [ -f "$out/comparison-cranium.md" ] && include=(--include "$out/comparison-cranium.md")
  others=()
  for m in fe fe-sinc; do [ -f "$out/cranium-methods/$m.vtk" ] && others+=("$out/cranium-methods/$m.vtk"); done
  "$me" report "$out/cranium" "$out/cranium-snert.vtk" "$out/cranium-high.vtk" "${others[@]}" \
    --title "Head CT (invesalius-examples, 256x256x108, 0.96x0.96x1.5 mm), bone at 300 HU" "${include[@]}"
  log "head CT: scale-space refinement of the unrelaxed SurfaceNets bone surface (about 1.5 minutes)"
  "$me" refine "$out/data/cranium.nhdr" "$out/cranium-refined.vtk" --initial surfacenets --iso 300 \
    --max-deviation 2 --target-quality 0.9 --csv "$out/refine-cranium.csv" --report > "$out/refine-cranium.txt"
  log "head CT as labels: soft tissue and bone in one pass, the faces between them shared"
  "$me" extract "$out/data/cranium.nhdr" "$out/cranium-labels.vtk" --label-thresholds -300,300 \
    --combined "$out/cranium-labels-combined.vtp" > "$out/cranium-labels.txt"
  "$me" report "$out/cranium-labels" "$out/cranium-labels-1.vtk" "$out/cranium-labels-2.vtk" \
    --title "Head CT as labels: soft tissue [-300, 300) HU (1) and bone >= 300 HU (2), one pass, shared faces"
  if [ -f "$out/data/headsq.nhdr" ] && [ -x "$compare" ]; then
    log "small head CT (../shared/data/ct_headsq): bone at 1150 (HU + 1024)"
    "$compare" "$out/data/headsq.nhdr" --iso 1150 --methods all --repeat 1 --markdown "$out/comparison-headsq.md" \
      --csv "$out/comparison-headsq.csv" > "$out/comparison-headsq.txt"
  fi
fi

# 3. Scale-space edge refinement (thesis ch. 4): the chapter-4 sphere (100^3, radius 25,
#    Gaussian noise sigma 2) from a geodesic sphere 3 mm too small, and the brain surface of
#    the Colin27 T1 MRI (mricron-data), where a threshold cannot separate brain from scalp:
#    the rough start is a SurfaceNets mesh of the brain-extracted image (ch2bet), refined
#    against the T1 image (ch2) itself.
log "chapter-4 sphere with noise: refine a geodesic sphere of radius 22 toward the edge at 25"
"$me" phantom chapter4-sphere "$out/chapter4-sphere-noise2.nrrd" --noise 2 --seed 1
"$me" refine "$out/chapter4-sphere-noise2.nrrd" "$out/chapter4-sphere-refined.vtk" --initial sphere --radius 22 \
  --max-deviation 4 --target-quality 0.9 --phantom chapter4-sphere --csv "$out/refine-chapter4-sphere.csv" \
  --report > "$out/refine-chapter4-sphere.txt"
templates=/usr/share/mricron/templates
if [ -f "$templates/ch2.nii.gz" ] && [ -f "$templates/ch2bet.nii.gz" ]; then
  log "Colin27 T1 MRI: brain surface by scale-space refinement of a rough SurfaceNets mesh"
  "$me" extract "$templates/ch2bet.nii.gz" --iso 1 --relaxation sna "$out/brain-rough.vtk"
  "$me" refine "$templates/ch2.nii.gz" "$out/brain-rough.vtk" "$out/brain-refined.vtk" --largest-component \
    --max-deviation 1.5 --target-quality 0.9 --csv "$out/refine-brain.csv" --report > "$out/refine-brain.txt"
  "$me" report "$out/brain" "$out/brain-rough.vtk" "$out/brain-refined.vtk" \
    --title "Colin27 T1 MRI (mricron-data, 181x217x181, 1 mm): brain surface, rough and refined"
else
  log "mricron-data is not installed: skipping the MRI refinement"
fi

# 3b. Connected orthogonal contours (chapter 5): the simulated user's table (Table 5.1's
#     analogue) on two phantoms and, with mricron-data, the Colin27 lateral ventricle.
log "Connected orthogonal contours: the simulated user (Table 5.1)"
build/examples/meshextraction-contours-study --markdown "$out/contours-study.md" > "$out/contours-study.txt"

# 4. An index page.
{
  echo "<!DOCTYPE html><html><head><meta charset='utf-8'><title>MeshExtraction results</title></head>"
  echo "<body style='font-family:sans-serif;margin:2em'><h1>MeshExtraction results</h1><ul>"
  for page in "$out"/*/index.html; do
    dir=$(basename "$(dirname "$page")")
    echo "<li><a href='$dir/index.html'>$dir</a></li>"
  done
  echo "</ul><p>Meshes: *.vtk next to this page; comparison tables: comparison-*.md.</p></body></html>"
} > "$out/index.html"
log "open $out/index.html"

# 5. The tables of doc/results.md from this run, in $out/results.md (doc/results.md is
#    replaced only by hand: python3 scripts/make-results-doc.py "$out" > doc/results.md).
if python3 scripts/make-results-doc.py "$out" > "$out/results.md.tmp"; then
  mv "$out/results.md.tmp" "$out/results.md"
  log "tables for doc/results.md: $out/results.md"
else
  rm -f "$out/results.md.tmp"
  log "make-results-doc.py failed: no $out/results.md"
fi

#!/usr/bin/env bash
# Cuts phantom images short in three formats (compressed MetaImage, NIfTI, NRRD) and fails
# unless `extract` refuses each with a message that names the file, and still reads
# the whole files. Used by the command-line test cli.extract_truncated_images.
set -u
tool=$1
out=$2
mkdir -p "$out"
for ext in mha nii nrrd; do
  whole="$out/whole.$ext"
  cut="$out/cut.$ext"
  "$tool" phantom sphere "$whole" --size 32 > /dev/null 2>&1 || { echo "could not write $whole"; exit 1; }
  size=$(stat -c %s "$whole")
  head -c $((size * 2 / 3)) "$whole" > "$cut"
  message=$("$tool" extract "$cut" "$out/x.vtk" --iso 0 2>&1)
  status=$?
  if [ $status -ne 1 ] || ! grep -q "cut.$ext" <<< "$message"; then
    echo "extract of a truncated .$ext: status $status, expected 1 and the file named:"
    echo "$message"
    exit 1
  fi
  "$tool" extract "$whole" "$out/x.vtk" --iso 0 > /dev/null 2>&1 || { echo "the whole .$ext was refused"; exit 1; }
done
echo "ok: truncated images refused, whole ones read"

#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The plain build: configured with the project's defaults (as a user's `cmake -S . -B b`), the
# module has no comparison technique: its configured header says so, it compiles, and its public
# headers, as a compiler sees them, declare no face partition or camera space option.
#   plain.sh <source dir> <work dir> <c++ compiler>
set -euo pipefail
source=$1 work=$2 cxx=$3
rm -rf "$work"
if ! cmake -S "$source" -B "$work" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
  > "$work.configure.log" 2>&1; then
  tail -n 20 "$work.configure.log"
  echo "FAIL: the plain build does not configure"
  exit 1
fi
grep -q "CSM_COMPARISON_TECHNIQUES:BOOL=OFF" "$work/CMakeCache.txt" ||
  { echo "FAIL: CSM_COMPARISON_TECHNIQUES is not off by default"; exit 1; }
configured="$work/Module/vtkCascadedShadowsConfigure.h"
grep -q "define CSM_COMPARISON_TECHNIQUES 0" "$configured" ||
  { echo "FAIL: $configured does not say 0"; exit 1; }
if ! cmake --build "$work" -j 2 --target RenderingCascadedShadows > "$work.build.log" 2>&1; then
  grep -E "error" "$work.build.log" | head -n 20
  echo "FAIL: the plain build's module does not compile"
  exit 1
fi
includes=(-I"$work/Module" -I"$source/Module" -I/usr/include/vtk-9.1)
found=0
for header in vtkCascadedShadowMapPass.h vtkCascadedShadowMapBakerPass.h \
  vtkCascadedShadowMapPlanner.h; do
  if ! echo "#include \"$header\"" | "$cxx" -std=c++17 -E -P -x c++ "${includes[@]}" - \
    > "$work/$header.i" 2> "$work/$header.log"; then
    cat "$work/$header.log"
    echo "FAIL: $header does not compile as a user's program includes it"
    exit 1
  fi
  # (The class itself must be there: a header that declares nothing would pass below.)
  grep -q "class .*${header%.h}" "$work/$header.i" ||
    { echo "FAIL: $header declares no ${header%.h}"; exit 1; }
  lines=$(grep -cE "FacePartition|CameraSpace|CascadePlanes|DepthW|SelectedByPlanes|FACE_Z" \
    "$work/$header.i" || true)
  echo "$header: $lines declarations of the comparison techniques"
  found=$((found + lines))
done
[[ $found -eq 0 ]] || { echo "FAIL: the plain build's headers declare comparison techniques"; exit 1; }
echo "the plain build has no comparison technique"

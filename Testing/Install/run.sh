#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The install test: install the build into a temporary prefix, move the prefix (it must be
# relocatable), build a downstream VTK application against it with find_package, run it (it
# fails when its picture has no shadow), and run an installed program from the prefix; with a
# Python interpreter, also run the Python test against the installed package cascadedshadows.
#   run.sh <build dir> <downstream source dir> <work dir> [<python3> <package dir in the prefix>]
set -euo pipefail
build=$1 source=$2 work=$3 python=${4:-} python_dir=${5:-}
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
mv "$work/prefix" "$work/moved"
if grep -rl "$build" "$work/moved/lib/cmake" "$work/moved/include"; then
  echo "the installed package refers to the build tree (above)"
  exit 1
fi
# The downstream project in both orders: find_package(VTK ...) after find_package(CascadedShadows),
# and before it (then the package must leave the caller's VTK_LIBRARIES as they were).
for order in csm-first vtk-first; do
  vtk_first=OFF
  [[ $order = vtk-first ]] && vtk_first=ON
  if ! cmake -S "$source" -B "$work/build-$order" -DCMAKE_PREFIX_PATH="$work/moved" \
    -DCMAKE_BUILD_TYPE=Release -DCSM_VTK_FIRST=$vtk_first > "$work/configure-$order.log" 2>&1 ||
    ! cmake --build "$work/build-$order" > "$work/build-$order.log" 2>&1; then
    tail -n 20 "$work/configure-$order.log" "$work/build-$order.log" 2>/dev/null
    echo "FAIL: the downstream project ($order) did not configure or build"
    exit 1
  fi
done
"$work/moved/bin/csm-demo" --help > /dev/null
"$work/moved/bin/csm-analyze" --near 0.5 --far 500 > /dev/null
# The downstream program uses VTK's own (X) window: a virtual display when there is none.
display=()
[[ -n "${DISPLAY:-}" ]] || display=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
for order in csm-first vtk-first; do
  "${display[@]}" "$work/build-$order/downstream" "$work/downstream-$order.png"
done
# The installed Python package, from the moved prefix (its extension finds the module there).
if [[ -n "$python" ]]; then
  bash "$source/../Python/run.sh" "$python" "$work/moved/$python_dir" \
    "$source/../Python/TestPythonShadows.py"
fi

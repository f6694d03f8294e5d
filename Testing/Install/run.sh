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
cmake -S "$source" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/moved" \
  -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
"$work/moved/bin/csm-demo" --help > /dev/null
"$work/moved/bin/csm-analyze" --near 0.5 --far 500 > /dev/null
# The downstream program uses VTK's own (X) window: a virtual display when there is none.
if [[ -n "${DISPLAY:-}" ]]; then
  "$work/build/downstream"
else
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$work/build/downstream"
fi
# The installed Python package, from the moved prefix (its extension finds the module there).
if [[ -n "$python" ]]; then
  bash "$source/../Python/run.sh" "$python" "$work/moved/$python_dir" \
    "$source/../Python/TestPythonShadows.py"
fi

#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs a Python test with the build's package cascadedshadows on PYTHONPATH. VTK's Python
# modules (python3-vtk9) are built for GLX only: the script gets the current display, or a
# virtual one (Xvfb) when there is none.
#   run.sh <python3> <build python dir> <script> [args...]
set -euo pipefail
python=$1 path=$2
shift 2
export PYTHONPATH="$path${PYTHONPATH:+:$PYTHONPATH}"
if [[ -n "${DISPLAY:-}" ]]; then
  exec "$python" "$@"
else
  exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$python" "$@"
fi

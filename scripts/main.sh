#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: set up, build, then render the default scene (the procedural platform, ~250k
# triangles) offscreen with our cascaded shadows and with VTK's own shadow pass, print the
# two frame times, and print the analytic speed-against-error table.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT="${CSM_OUT_DIR:-$BUILD/output}"
mkdir -p "$OUT"
for technique in csm vtk; do
  echo "== technique $technique"
  run_gl "$BUILD/Examples/csm-demo" --offscreen --technique "$technique" --frames 12 \
    --out "$OUT/platform-$technique.png"
done
echo "== analytic storage factor of common settings (csm-analyze --table)"
"$BUILD/Examples/csm-analyze" --table

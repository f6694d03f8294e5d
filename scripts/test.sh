#!/usr/bin/env bash
# The tests: set up (packages, the ParaView prefix), build, then run every CTest test (GL tests
# under a virtual display). CSM_PREPARE_PARAVIEW=0 leaves the ParaView prefix out (the paraview.*
# tests are then skipped, unless an earlier run prepared it).
set -euo pipefail
CSM_PREPARE_PARAVIEW="${CSM_PREPARE_PARAVIEW:-1}"
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$BUILD"
with_display ctest --output-on-failure "$@"

#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The tests: set up (packages, the ParaView prefix), build, then run every CTest test. With the
# OSMesa window (the default where libosmesa6-dev is installed, which setup.sh installs) ctest
# runs with no X server at all (DISPLAY unset); only the ParaView tests (pvbatch has its own,
# GLX-only VTK) and the install test's downstream program start their own Xvfb. Without it,
# every test runs under a virtual display. CSM_PREPARE_PARAVIEW=0 leaves the ParaView prefix out
# (the paraview.* tests are then skipped, unless an earlier run prepared it).
set -euo pipefail
CSM_PREPARE_PARAVIEW="${CSM_PREPARE_PARAVIEW:-1}"
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$BUILD"
if osmesa_build; then
  echo "GL tests through OSMesa, no X server (DISPLAY unset); ParaView tests under their own Xvfb"
  env -u DISPLAY ctest --output-on-failure "$@"
else
  echo "GL tests under a display (this build has no OSMesa window)"
  with_display ctest --output-on-failure "$@"
fi

#!/usr/bin/env bash
# The tests: set up, build, then run every CTest test. With the OSMesa window (the default where
# libosmesa6-dev is installed, which setup.sh installs) ctest runs with no X server at all
# (DISPLAY unset); only the ParaView tests start their own Xvfb (pvbatch has its own, GLX-only
# VTK). Without it, every test runs under a virtual display.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$BUILD"
if osmesa_build; then
  echo "GL tests through OSMesa, no X server (DISPLAY unset); ParaView tests under their own Xvfb"
  env -u DISPLAY ctest --output-on-failure "$@"
else
  echo "GL tests under a display (this build has no OSMesa window)"
  with_display ctest --output-on-failure "$@"
fi

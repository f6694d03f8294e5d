#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The Debian package: set up and build as the other scripts do, then CPack writes
# build/vtk-cascaded-shadows_<version>_<arch>.deb (install it with `apt install ./<file>.deb`).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$BUILD"
cpack -G DEB > "$BUILD/logs/cpack.log" 2>&1 || { tail -20 "$BUILD/logs/cpack.log"; exit 1; }
ls -1 "$BUILD"/*.deb

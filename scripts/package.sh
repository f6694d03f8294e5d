#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The Debian package: set up and build as the other scripts do, then CPack writes
# build-deb/vtk-cascaded-shadows_<version>_<arch>.deb (install it with `apt install ./<file>.deb`).
set -euo pipefail
# A build of its own, configured for /usr: GNUInstallDirs then puts the libraries in Debian's
# multiarch directory (lib/<triplet>) and the Python package in /usr/lib/python3/dist-packages.
# The package is a user's build: without the comparison techniques of the benchmark (the OFF
# comes last, after setup.sh's ON and any CSM_CMAKE_ARGS given).
ROOT_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export CSM_BUILD_DIR="${CSM_BUILD_DIR:-$ROOT_DIR/build-deb}"
export CSM_CMAKE_ARGS="-DCMAKE_INSTALL_PREFIX=/usr ${CSM_CMAKE_ARGS:-} -DCSM_COMPARISON_TECHNIQUES=OFF"
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$BUILD"
cpack -G DEB > "$BUILD/logs/cpack.log" 2>&1 || { tail -20 "$BUILD/logs/cpack.log"; exit 1; }
ls -1 "$BUILD"/*.deb

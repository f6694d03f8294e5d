#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The Debian packages (README, "Debian packages"), split as Debian splits VTK's, into build-deb/
# (or $CSM_BUILD_DIR): the library, its -dev package, the python3- package and the programs
# from the module's build, and the ParaView 5.11 plugin from the plugin's build against
# Debian's ParaView (build-deb/paraview). Install them with `apt install ./<file>.deb`;
# scripts/package-test.sh builds, installs, checks and removes them.
set -euo pipefail
# Builds of their own, configured for /usr: GNUInstallDirs then puts the libraries in Debian's
# multiarch directory (lib/<triplet>) and the Python package in /usr/lib/python3/dist-packages.
# The packages are a user's build: without the comparison techniques of the benchmark (the OFF
# comes last, after setup.sh's ON and any CSM_CMAKE_ARGS given) and without the tests.
ROOT_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export CSM_BUILD_DIR="${CSM_BUILD_DIR:-$ROOT_DIR/build-deb}"
export CSM_CMAKE_ARGS="-DCMAKE_INSTALL_PREFIX=/usr ${CSM_CMAKE_ARGS:-} -DCSM_COMPARISON_TECHNIQUES=OFF -DBUILD_TESTING=OFF -DCSM_MANPAGES=ON"
# What packaging needs beyond the build: dpkg-shlibdeps (dpkg-dev) and file for CPack, help2man
# for the programs' manual pages; then setup.sh installs the build's packages and builds.
source "$ROOT_DIR/scripts/common.sh"
LOGS="$CSM_BUILD_DIR/logs"
PACKAGES=(dpkg-dev file help2man)
install_missing_packages
source "$ROOT_DIR/scripts/setup.sh"

rm -f "$BUILD"/*.deb
(cd "$BUILD" && cpack -G DEB) >"$LOGS/cpack.log" 2>&1 ||
  { tail -n 20 "$LOGS/cpack.log" >&2; die "CPack failed (full log: $LOGS/cpack.log)"; }

# The plugin: Debian's paraview and paraview-dev from apt, their files (and python3-paraview's,
# which their CMake config needs) unpacked into $PV/prefix by scripts/paraview.sh; the plugin
# is configured against that prefix, for /usr.
PV="$BUILD/paraview"
mkdir -p "$PV/logs"
CSM_PV_BUILD_DIR="$PV" bash "$ROOT/scripts/paraview.sh" prepare >"$PV/logs/prepare.log" 2>&1 ||
  { tail -n 5 "$PV/logs/prepare.log" >&2; die "could not prepare ParaView (full log: $PV/logs/prepare.log)"; }
if ! cmake -S "$ROOT/ParaView" -B "$PV" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DParaView_DIR="$PV/prefix/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11" \
  -DCSM_COMPARISON_TECHNIQUES=OFF >"$PV/logs/configure.log" 2>&1; then
  grep -A5 "CMake Error" "$PV/logs/configure.log" | head -n 20 >&2 || true
  die "CMake configure of the plugin failed (full log: $PV/logs/configure.log)"
fi
cmake --build "$PV" -j "$(nproc)" >"$PV/logs/build.log" 2>&1 ||
  { grep -E "error|Error" "$PV/logs/build.log" | head -n 20 >&2; die "build of the plugin failed (full log: $PV/logs/build.log)"; }
rm -f "$PV"/*.deb
(cd "$PV" && cpack -G DEB) >"$PV/logs/cpack.log" 2>&1 ||
  { tail -n 20 "$PV/logs/cpack.log" >&2; die "CPack of the plugin failed (full log: $PV/logs/cpack.log)"; }
mv "$PV"/*.deb "$BUILD/"
ls -1 "$BUILD"/*.deb

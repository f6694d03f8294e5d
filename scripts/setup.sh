#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Shared set-up for the README commands: install the Debian packages that are missing, then
# configure and build in Release; with CSM_PREPARE_PARAVIEW=1 (test.sh) also prepare the ParaView
# prefix of the paraview.* tests. Sourced by main.sh, test.sh and benchmark.sh.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$ROOT/scripts/common.sh"
BUILD="${CSM_BUILD_DIR:-$ROOT/build}"
LOGS="$BUILD/logs"
PACKAGES=(cmake g++ make pkg-config libvtk9-dev libglm-dev libgtest-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri libosmesa6-dev assimp-testmodels libembree-dev openmpi-bin clang-format
  python3-vtk9 python3-numpy)

configure_and_build() {
  mkdir -p "$LOGS"
  echo "Configuring and building in $BUILD (Release)"
  # The comparison techniques (face partitioning, camera space maps) are on in this build: the
  # benchmark and their tests need them. CSM_CMAKE_ARGS comes after and may turn them off.
  # shellcheck disable=SC2086 # CSM_CMAKE_ARGS: more -D options, split on spaces (package.sh)
  if ! cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCSM_COMPARISON_TECHNIQUES=ON \
    ${CSM_CMAKE_ARGS:-} >"$LOGS/configure.log" 2>&1; then
    grep -A5 "CMake Error" "$LOGS/configure.log" | head -n 20 >&2 || tail -n 20 "$LOGS/configure.log" >&2
    die "CMake configure failed (full log: $LOGS/configure.log)"
  fi
  if ! cmake --build "$BUILD" -j "$(nproc)" >"$LOGS/build.log" 2>&1; then
    grep -E "error|Error" "$LOGS/build.log" | head -n 20 >&2
    die "build failed (full log: $LOGS/build.log)"
  fi
}

# The ParaView prefix the paraview.* tests use (they install nothing themselves): prepared when
# the caller asks (scripts/test.sh), where CTest looks for it.
prepare_paraview_prefix() {
  mkdir -p "$LOGS"
  if ! CSM_PV_BUILD_DIR="$BUILD/paraview" bash "$ROOT/scripts/paraview.sh" prepare \
    >"$LOGS/paraview-prepare.log" 2>&1; then
    tail -n 5 "$LOGS/paraview-prepare.log" >&2
    die "could not prepare the ParaView prefix (full log: $LOGS/paraview-prepare.log)"
  fi
}

install_missing_packages
[ "${CSM_PREPARE_PARAVIEW:-0}" = 1 ] && prepare_paraview_prefix
configure_and_build

#!/usr/bin/env bash
# Shared set-up for the README commands: install the Debian packages that are missing, then
# configure and build in Release. Sourced by main.sh, test.sh and benchmark.sh.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$ROOT/scripts/common.sh"
BUILD="${CSM_BUILD_DIR:-$ROOT/build}"
LOGS="$BUILD/logs"
PACKAGES=(cmake g++ make pkg-config libvtk9-dev libglm-dev libgtest-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri libosmesa6-dev assimp-testmodels libembree-dev openmpi-bin)

configure_and_build() {
  mkdir -p "$LOGS"
  echo "Configuring and building in $BUILD (Release)"
  if ! cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >"$LOGS/configure.log" 2>&1; then
    grep -A5 "CMake Error" "$LOGS/configure.log" | head -n 20 >&2 || tail -n 20 "$LOGS/configure.log" >&2
    die "CMake configure failed (full log: $LOGS/configure.log)"
  fi
  if ! cmake --build "$BUILD" -j "$(nproc)" >"$LOGS/build.log" 2>&1; then
    grep -E "error|Error" "$LOGS/build.log" | head -n 20 >&2
    die "build failed (full log: $LOGS/build.log)"
  fi
}

install_missing_packages
configure_and_build

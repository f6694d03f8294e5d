#!/usr/bin/env bash
# Shared set-up for the README commands: install the Debian packages that are missing, then
# configure and build in Release. Sourced by main.sh, test.sh and benchmark.sh.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${CSM_BUILD_DIR:-$ROOT/build}"
LOGS="$BUILD/logs"
PACKAGES=(cmake g++ make pkg-config libvtk9-dev libglm-dev libgtest-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri assimp-testmodels libembree-dev openmpi-bin)

die() { echo "error: $*" >&2; exit 1; }

install_missing_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "Installing Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || die "packages missing (${missing[*]}) and not root; install them with apt-get"
    sudo="sudo"
  fi
  mkdir -p "$LOGS"
  if ! { $sudo apt-get update -q && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"; } >"$LOGS/apt.log" 2>&1; then
    tail -n 5 "$LOGS/apt.log" >&2
    die "could not install the Debian packages: ${missing[*]} (full log: $LOGS/apt.log)"
  fi
}

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

# Runs a command with a display: the current one, else a virtual X server (Mesa llvmpipe).
with_display() {
  if [ -n "${DISPLAY:-}" ]; then
    "$@"
  else
    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"
  fi
}

install_missing_packages
configure_and_build

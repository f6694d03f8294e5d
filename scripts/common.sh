#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Shared by the scripts: one-line errors, installing the missing Debian packages of $PACKAGES
# (logs in $LOGS), and running a command with a display (or without one, through OSMesa).

die() { echo "error: $*" >&2; exit 1; }

install_missing_packages() {
  local missing=() p sudo=""
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "Installing Debian packages: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || die "packages missing (${missing[*]}) and not root; install them with apt-get"
    sudo="sudo"
  fi
  mkdir -p "$LOGS"
  # No recommends: paraview recommends python3-paraview, which would remove python3-vtk9 and
  # libvtk9-dev; --no-remove makes apt stop rather than remove anything.
  if ! { $sudo apt-get update -q &&
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends \
      --no-remove "${missing[@]}"; } >"$LOGS/apt.log" 2>&1; then
    tail -n 5 "$LOGS/apt.log" >&2
    die "could not install the Debian packages: ${missing[*]} (full log: $LOGS/apt.log)"
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

# Whether the build in $BUILD links the OSMesa window (CMake option CSM_OSMESA; on by default
# where libosmesa6-dev is installed): its GL tests, csm-demo --offscreen and csm-bench render
# with no X server.
osmesa_build() {
  grep -q '^CSM_OSMESA_IN_USE:INTERNAL=ON$' "$BUILD/CMakeCache.txt" 2>/dev/null
}

# Runs an offscreen GL program of the build: with no X server (DISPLAY unset) through OSMesa,
# else with a display.
run_gl() {
  if osmesa_build; then
    env -u DISPLAY "$@"
  else
    with_display "$@"
  fi
}

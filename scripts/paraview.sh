#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The ParaView 5.11 plugin (ParaView/): install what it needs, build it against ParaView's own
# VTK, and run its pvbatch tests: one process (image against the baseline, shadow pixel count,
# selection, properties, tube shadows), 2 MPI ranks (shadows cast across the ranks' pieces),
# the pvpython snippets of README.md and ParaView/README.md run as written (a shadow shows), and
# the XML's default_values against the passes' getters.
#
# Debian's ParaView CMake config refers to files of python3-paraview, which conflicts with
# python3-vtk9 (needed by libvtk9-dev, the main build). So paraview and paraview-dev come from
# apt (they bring the runtime libraries), and paraview, paraview-dev and python3-paraview of the
# same version are unpacked into $BUILD/prefix (dpkg -x): the plugin is configured against that
# prefix and the test runs its pvbatch. Nothing of the libvtk9 build is used.
#
#   bash scripts/paraview.sh [all|prepare|single|mpi|readme|defaults]
#   build dir: build-paraview/ (or $CSM_PV_BUILD_DIR)
#   CSM_COMPARISON_TECHNIQUES=ON: the plugin with the comparison techniques (off by default, as
#   for a user; CTest's paraview.* tests pass the main build's setting)
#   all (default): prepare, build, run every test. prepare: install the packages and unpack
#   the prefix, nothing else (scripts/test.sh runs it, through setup.sh). The other modes run
#   one test each and install and unpack nothing (CTest: paraview.View, paraview.ViewMPI,
#   paraview.Readme, paraview.Defaults): they build the plugin in the prepared prefix, or exit
#   with status 77 (skipped) when there is none.
set -euo pipefail
MODE="${1:-all}"
case "$MODE" in all|prepare|single|mpi|readme|defaults) ;;
  *) echo "error: unknown mode '$MODE' (all, prepare, single, mpi, readme or defaults)" >&2; exit 2 ;;
esac

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$ROOT/scripts/common.sh"
BUILD="${CSM_PV_BUILD_DIR:-$ROOT/build-paraview}"
PREFIX="$BUILD/prefix"
LOGS="$BUILD/logs"
PV_LIB="$PREFIX/usr/lib/x86_64-linux-gnu"
PACKAGES=(cmake g++ make pkg-config libglm-dev xvfb xauth libgl1-mesa-dri
  paraview paraview-dev python3-dev python3-numpy mpi-default-dev openmpi-bin
  # development files ParaView's VTK config looks for (listed from a configure's CMakeCache)
  libeigen3-dev libexpat1-dev libfreetype-dev libfontconfig-dev libglew-dev libjpeg-dev
  liblz4-dev liblzma-dev libpng-dev libtiff-dev zlib1g-dev libdouble-conversion-dev
  libutfcpp-dev libx11-dev libxt-dev libgl-dev libegl-dev libgles-dev libglu1-mesa-dev)

mkdir -p "$LOGS"

unpack_paraview_prefix() {
  local version
  version="$(dpkg-query -W -f='${Version}' paraview)"
  if [ -f "$PREFIX/.version" ] && [ "$(cat "$PREFIX/.version")" = "$version" ]; then
    return 0
  fi
  echo "Unpacking paraview, paraview-dev and python3-paraview $version into $PREFIX"
  rm -rf "$PREFIX" "$BUILD/debs"
  mkdir -p "$BUILD/debs" "$PREFIX"
  chmod 777 "$BUILD/debs" # apt-get download runs as _apt when it can
  if ! (cd "$BUILD/debs" && apt-get download "paraview=$version" "paraview-dev=$version" \
    "python3-paraview=$version") >"$LOGS/download.log" 2>&1; then
    tail -n 5 "$LOGS/download.log" >&2
    die "could not download the ParaView $version packages (full log: $LOGS/download.log)"
  fi
  for deb in "$BUILD"/debs/*.deb; do
    dpkg -x "$deb" "$PREFIX" || die "could not unpack $deb"
  done
  echo "$version" >"$PREFIX/.version"
}

configure_and_build() {
  echo "Configuring and building the plugin in $BUILD (Release)"
  if ! cmake -S "$ROOT/ParaView" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release \
    -DParaView_DIR="$PV_LIB/cmake/paraview-5.11" \
    -DCSM_COMPARISON_TECHNIQUES="${CSM_COMPARISON_TECHNIQUES:-OFF}" >"$LOGS/configure.log" 2>&1; then
    grep -A5 "CMake Error" "$LOGS/configure.log" | head -n 20 >&2 ||
      tail -n 20 "$LOGS/configure.log" >&2
    die "CMake configure of the plugin failed (full log: $LOGS/configure.log)"
  fi
  if ! cmake --build "$BUILD" -j "$(nproc)" >"$LOGS/build.log" 2>&1; then
    grep -E "error|Error" "$LOGS/build.log" | head -n 20 >&2
    die "build of the plugin failed (full log: $LOGS/build.log)"
  fi
}

if [ "$MODE" = all ] || [ "$MODE" = prepare ]; then
  install_missing_packages
  unpack_paraview_prefix
  [ "$MODE" = prepare ] && exit 0
elif [ ! -f "$PREFIX/.version" ] || ! command -v xvfb-run >/dev/null; then
  echo "SKIP: no ParaView prefix in $PREFIX (or no xvfb-run): bash scripts/test.sh prepares" \
    "it, or bash scripts/paraview.sh prepare with CSM_PV_BUILD_DIR=$BUILD"
  exit 77
fi
configure_and_build

PLUGIN="$BUILD/lib/paraview-5.11/plugins/CascadedShadows/CascadedShadows.so"
[ -f "$PLUGIN" ] || die "the build produced no plugin at $PLUGIN"
TESTING="$ROOT/ParaView/Testing"
XVFB=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
MPIEXEC=(mpiexec -np 2 --oversubscribe -x LD_LIBRARY_PATH -x DISPLAY)
[ "$(id -u)" -eq 0 ] && MPIEXEC+=(--allow-run-as-root)
# ParaView's pvbatch and libraries from the prefix; a PYTHONPATH to another VTK must not leak in.
unset PYTHONPATH
export LD_LIBRARY_PATH="$PV_LIB${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
failed=()

if [ "$MODE" = all ] || [ "$MODE" = single ]; then
  echo "== pvbatch test, 1 process (Xvfb, Mesa llvmpipe): $PLUGIN"
  "${XVFB[@]}" "$PREFIX/usr/bin/pvbatch" "$TESTING/TestCascadedShadowsView.py" "$PLUGIN" \
    "$TESTING/Baseline/CascadedShadowsView.png" "$BUILD/Testing" 2>&1 | tee "$LOGS/test.log" ||
    failed+=("1 process (log: $LOGS/test.log)")
fi

if [ "$MODE" = all ] || [ "$MODE" = mpi ]; then
  echo "== pvbatch test, 2 MPI ranks (IceT)"
  timeout 600 "${XVFB[@]}" "${MPIEXEC[@]}" "$PREFIX/usr/bin/pvbatch" --mpi \
    "$TESTING/TestCascadedShadowsViewMPI.py" "$PLUGIN" "$BUILD/Testing" 2>&1 |
    tee "$LOGS/test-mpi.log" | { grep -v "WARN|" || true; } ||
    failed+=("2 MPI ranks (log: $LOGS/test-mpi.log)")
fi

if [ "$MODE" = all ] || [ "$MODE" = readme ]; then
  : >"$LOGS/test-readme.log"
  for readme in README.md ParaView/README.md; do
    echo "== pvbatch: the pvpython snippet of $readme, run as written"
    "${XVFB[@]}" "$PREFIX/usr/bin/pvbatch" "$TESTING/TestReadmeSnippet.py" "$ROOT/$readme" \
      "$BUILD" "$BUILD/Testing/readme" 2>&1 | tee -a "$LOGS/test-readme.log" ||
      failed+=("snippet of $readme (log: $LOGS/test-readme.log)")
  done
fi

if [ "$MODE" = all ] || [ "$MODE" = defaults ]; then
  echo "== pvbatch: each default_values of the plugin's XML against the C++ getter"
  "${XVFB[@]}" "$PREFIX/usr/bin/pvbatch" "$TESTING/TestXMLDefaults.py" "$PLUGIN" \
    "$BUILD/CascadedShadowsView.xml" 2>&1 | tee "$LOGS/test-defaults.log" ||
    failed+=("XML defaults (log: $LOGS/test-defaults.log)")
fi

[ ${#failed[@]} -eq 0 ] || die "ParaView plugin test failed: ${failed[*]}; images in $BUILD/Testing"
echo "ParaView plugin tests passed"

#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The Debian packages as their users meet them (README, "Debian packages"): builds them
# (scripts/package.sh), runs lintian on each (no errors), installs them on this machine with
# `apt install ./<file>.deb` (root or sudo), checks each as its user would, and removes them
# again, also when a check fails:
#   - the library and python3- packages pull in no -dev package;
#   - python3-cascadedshadows: /usr/bin/python3, no PYTHONPATH, imports the passes and runs the
#     Python snippet of README.md as written (the picture must show the box's shadow);
#   - the -dev package: a CMake project (Testing/Install) finds the module under /usr, builds,
#     and its program renders a shadow;
#   - cascadedshadows-tools: csm-demo --offscreen renders with no display; the manual pages;
#   - paraview-cascadedshadows: ParaView's GUI lists the plugin (Tools > Manage Plugins), and
#     pvbatch loads it by name, LoadDistributedPlugin("CascadedShadows"), in place of the
#     LoadPlugin line of README.md's ParaView snippet, and the rest runs as written (a shadow).
# ParaView's Python modules (python3-paraview) conflict with python3-vtk9, which the build and the
# python3- package need: where python3-paraview is not installed, pvbatch and the GUI get them
# from the copy scripts/package.sh unpacked (PYTHONPATH); the plugin is found without help.
#   bash scripts/package-test.sh     (build dir: build-deb/, or $CSM_BUILD_DIR; work: build-deb/package-test)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$ROOT/scripts/common.sh"
BUILD="${CSM_BUILD_DIR:-$ROOT/build-deb}"
WORK="$BUILD/package-test"
LOGS="$WORK/logs"
PACKAGES=(lintian xvfb xauth libgl1-mesa-dri cmake g++ make)
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"

echo "== building the packages (scripts/package.sh)"
bash "$ROOT/scripts/package.sh"
rm -rf "$WORK"
mkdir -p "$LOGS"
install_missing_packages
mapfile -t DEBS < <(ls "$BUILD"/*.deb)
NAMES=()
for deb in "${DEBS[@]}"; do NAMES+=("$(dpkg-deb -f "$deb" Package)"); done
pkg() { printf '%s\n' "${NAMES[@]}" | grep -E -e "$1"; }
LIB=$(pkg '^libvtk.*[0-9]$') DEV=$(pkg '-dev$') PY=$(pkg '^python3-') TOOLS=$(pkg '-tools$')
PLUGIN=$(pkg '^paraview-')

echo "== lintian (errors fail; warnings are fixed or overridden with a reason: Packaging/lintian)"
lintian_errors=0
for deb in "${DEBS[@]}"; do
  echo "-- $(basename "$deb")"
  lintian --show-overrides "$deb" 2>&1 | grep -E "^[EWIPO]: " || echo "(no tags)"
  lintian "$deb" 2>/dev/null | grep -q "^E:" && lintian_errors=1
done
[ "$lintian_errors" = 0 ] || die "lintian reports errors (above)"

remove_packages() {
  local installed=() name
  for name in "${NAMES[@]}"; do
    dpkg-query -W -f='${Status}' "$name" 2>/dev/null | grep -q "ok installed" && installed+=("$name")
  done
  [ ${#installed[@]} -eq 0 ] && return 0
  echo "== removing the packages: ${installed[*]}"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get purge -y -q "${installed[@]}" >"$LOGS/apt-remove.log" 2>&1 ||
    { tail -n 5 "$LOGS/apt-remove.log" >&2; echo "error: could not remove ${installed[*]}" >&2; exit 1; }
}
trap remove_packages EXIT
echo "== apt install ./*.deb"
# --no-remove: apt stops rather than remove anything (python3-paraview, say).
if ! DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends --no-remove \
  "${DEBS[@]}" >"$LOGS/apt-install.log" 2>&1; then
  tail -n 5 "$LOGS/apt-install.log" >&2
  die "apt could not install the packages (full log: $LOGS/apt-install.log)"
fi
for name in "${NAMES[@]}"; do
  dpkg-query -W -f='${Package} ${Version}: ${Depends}\n' "$name"
done
failed=()

echo "== the library and python3- packages pull in no -dev package"
for name in "$LIB" "$PY"; do
  apt-cache depends "$name"
  dev=$(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks \
    --no-replaces --no-enhances "$name" | grep -E '^[a-z0-9]' | grep -E -- '-dev$' || true)
  if [ -n "$dev" ]; then
    failed+=("$name pulls in: $(echo "$dev" | tr '\n' ' ')")
  else
    echo "$name: no -dev package among all its dependencies"
  fi
done

# Each check runs in its own directory with no PYTHONPATH, LD_LIBRARY_PATH or plugin path.
unset PYTHONPATH LD_LIBRARY_PATH PV_PLUGIN_PATH PV_PLUGIN_CONFIG_FILE

echo "== $PY: /usr/bin/python3 imports the passes and runs README.md's Python snippet"
mkdir -p "$WORK/python"
(cd "$WORK/python" && /usr/bin/python3 -c \
  "from cascadedshadows import vtkCascadedShadowMapPass; print(vtkCascadedShadowMapPass.__module__)") ||
  failed+=("$PY: import")
(cd "$WORK/python" && with_display /usr/bin/python3 "$ROOT/Testing/Python/TestReadmeSnippet.py" \
  "$ROOT/README.md" "$WORK/python") 2>&1 | tee "$LOGS/python.log" || failed+=("$PY: README snippet")

echo "== $DEV: a CMake project finds CascadedShadows under /usr, builds and renders"
if cmake -S "$ROOT/Testing/Install" -B "$WORK/downstream" -DCMAKE_BUILD_TYPE=Release \
  >"$LOGS/downstream-configure.log" 2>&1 &&
  cmake --build "$WORK/downstream" -j "$(nproc)" >"$LOGS/downstream-build.log" 2>&1; then
  grep -h "CascadedShadows_DIR:PATH" "$WORK/downstream/CMakeCache.txt"
  with_display "$WORK/downstream/downstream" "$WORK/downstream/downstream.png" &&
    echo "downstream program: shadow drawn, $WORK/downstream/downstream.png" ||
    failed+=("$DEV: the downstream program")
else
  tail -n 10 "$LOGS"/downstream-*.log
  failed+=("$DEV: the downstream project did not configure or build")
fi

echo "== $TOOLS: csm-demo --offscreen with no display; csm-analyze; manual pages"
(cd "$WORK" && env -u DISPLAY csm-demo --offscreen --out "$WORK/csm-demo.png" --frames 3) 2>&1 |
  tee "$LOGS/csm-demo.log" && [ -s "$WORK/csm-demo.png" ] || failed+=("$TOOLS: csm-demo --offscreen")
csm-analyze --near 1 --far 100 --cascades 3 >/dev/null || failed+=("$TOOLS: csm-analyze")
man -w csm-demo csm-bench csm-analyze || failed+=("$TOOLS: manual pages")

echo "== $PLUGIN: the GUI lists it (Tools > Manage Plugins); pvbatch loads it by name"
pv_python=()
if ! dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  pv_python=(env "PYTHONPATH=$BUILD/paraview/prefix/usr/lib/python3/dist-packages")
  echo "(ParaView's Python modules from $BUILD/paraview/prefix: python3-paraview conflicts with python3-vtk9)"
fi
cat >"$WORK/manage-plugins.py" <<EOF
from paraview import servermanager
info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
names = [info.GetPluginName(i) for i in range(info.GetNumberOfPlugins())]
open("$WORK/manage-plugins.txt", "w").write("\n".join(names) + "\n")
EOF
(cd "$WORK" && timeout 300 "${pv_python[@]}" xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  /usr/bin/paraview --script="$WORK/manage-plugins.py" --exit) >"$LOGS/paraview-gui.log" 2>&1 || true
if grep -qx CascadedShadows "$WORK/manage-plugins.txt" 2>/dev/null; then
  echo "paraview (GUI): Tools > Manage Plugins lists CascadedShadows among" \
    "$(wc -l <"$WORK/manage-plugins.txt") plugins"
else
  failed+=("$PLUGIN: the GUI does not list the plugin (log: $LOGS/paraview-gui.log)")
fi
# README.md with its ParaView snippet's LoadPlugin(<path>, ...) line loading the plugin by name.
sed 's|^LoadPlugin("build-paraview/[^"]*",$|LoadDistributedPlugin("CascadedShadows",|' \
  "$ROOT/README.md" >"$WORK/README.md"
grep -q '^LoadDistributedPlugin("CascadedShadows",$' "$WORK/README.md" ||
  failed+=("README.md's ParaView snippet has no LoadPlugin(\"build-paraview/...\", line to replace")
(cd "$WORK" && "${pv_python[@]}" xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" /usr/bin/pvbatch \
  "$ROOT/ParaView/Testing/TestReadmeSnippet.py" "$WORK/README.md" "$WORK" "$WORK/pvbatch") 2>&1 |
  tee "$LOGS/pvbatch.log" || failed+=("$PLUGIN: pvbatch, README's snippet with LoadDistributedPlugin")

[ ${#failed[@]} -eq 0 ] || die "package test failed: ${failed[*]}"
echo "package test passed: ${NAMES[*]}"

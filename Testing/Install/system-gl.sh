#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The installed window program (csm-demo) takes GL from the system, not from OSMesa:
#  1. neither it nor any library it needs needs libOSMesa or libcsm_headless (readelf -d, ldd);
#  2. with DISPLAY unset, --offscreen still renders: the program runs itself again with
#     libcsm_headless and libOSMesa preloaded (the loader's log shows libOSMesa loaded);
#  3. with the OSMesa window turned off (CSM_HEADLESS=x) it renders through GLX on a display (an
#     Xvfb when there is none), and libOSMesa is never loaded.
#   system-gl.sh <installed prefix> <work dir>
set -uo pipefail
prefix=$1 work=$2
demo="$prefix/bin/csm-demo"
mkdir -p "$work"
failed=0
fail() { echo "FAIL: $*"; failed=1; }
args=(--size 200x150 --triangles 20000 --technique csm)

[[ -x "$demo" ]] || { echo "FAIL: no $demo (run install.Downstream first)"; exit 1; }
if readelf -d "$demo" | grep -E "NEEDED.*(OSMesa|csm_headless)"; then
  fail "csm-demo needs the libraries above"
fi
ldd "$demo" > "$work/ldd.txt"
if grep -E "OSMesa|csm_headless" "$work/ldd.txt"; then
  fail "csm-demo loads the libraries above"
fi
grep -qE "libGLX?\.so" "$work/ldd.txt" || fail "csm-demo loads no system GL (libGL/libGLX)"
[[ $failed = 0 ]] &&
  echo "ok: csm-demo needs no libOSMesa (readelf -d, ldd: $(grep -oE 'libGLX?\.so[.0-9]*' "$work/ldd.txt" | sort -u | tr '\n' ' '))"

# Only the loader's log of which files it loads (LD_DEBUG=files), not the program's output.
loaded() { grep -oE "file=[^ ]*OSMesa[^ ]*" "$1" | sort -u; }

rm -f "$work/headless.png" "$work"/headless.ld.*
if ! env -u DISPLAY LD_DEBUG=files LD_DEBUG_OUTPUT="$work/headless.ld" \
  "$demo" --offscreen --out "$work/headless.png" "${args[@]}" > "$work/headless.log" 2>&1; then
  cat "$work/headless.log"
  fail "csm-demo --offscreen with DISPLAY unset failed"
elif [[ ! -s "$work/headless.png" ]]; then
  fail "csm-demo --offscreen with DISPLAY unset wrote no picture"
elif [[ -z "$(cat "$work"/headless.ld.* | loaded /dev/stdin)" ]]; then
  fail "csm-demo --offscreen rendered with DISPLAY unset but did not load libOSMesa"
else
  echo "ok: csm-demo --offscreen, DISPLAY unset: $(stat -c %s "$work/headless.png") byte picture through $(cat "$work"/headless.ld.* | loaded /dev/stdin | head -n 1)"
fi

display=()
[[ -n "${DISPLAY:-}" ]] || display=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
rm -f "$work/glx.png" "$work"/glx.ld.*
if ! CSM_HEADLESS=x "${display[@]}" env LD_DEBUG=files LD_DEBUG_OUTPUT="$work/glx.ld" \
  "$demo" --offscreen --out "$work/glx.png" "${args[@]}" > "$work/glx.log" 2>&1; then
  cat "$work/glx.log"
  fail "csm-demo through GLX (CSM_HEADLESS=x) failed"
elif [[ ! -s "$work/glx.png" ]]; then
  fail "csm-demo through GLX wrote no picture"
elif [[ -n "$(cat "$work"/glx.ld.* | loaded /dev/stdin)" ]]; then
  fail "csm-demo through GLX loaded libOSMesa"
else
  echo "ok: csm-demo through GLX (system GL): $(stat -c %s "$work/glx.png") byte picture, libOSMesa not loaded"
fi
exit $failed

#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The module and the tests that exercise its threads, its passes and its math, built and run
# under the sanitizers: ThreadSanitizer in build-tsan/, AddressSanitizer with
# UndefinedBehaviorSanitizer in build-asan/ (each its own build, RelWithDebInfo). Installs what
# is missing, as the test command does. Exits non-zero on any report.
#   bash scripts/sanitize.sh [thread|address]   (both by default)
# Suppressions (scripts/sanitize/): only for frames outside the project (Mesa's llvmpipe
# threads and VTK's own), each named and explained in its file.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$ROOT/scripts/common.sh"
LOGS="$ROOT/build-sanitize-logs"
PACKAGES=(cmake g++ make pkg-config libvtk9-dev libglm-dev libgtest-dev xvfb xauth
  libgl1-mesa-dri libosmesa6-dev libembree-dev openmpi-bin)
install_missing_packages

# The tests run: the math, the planner, the passes (the worker threads' preparations of big
# meshes among them, with the in-place edits of a mesh under preparation).
TARGETS=(csmMathTests csmModuleTests csmPassTests)
# (Not the test of resident memory across on/off cycles: a sanitizer's shadow memory is what it
# would measure.)
FILTER="${CSM_SANITIZE_FILTER:-*-Frames.SwitchingShadowsOnAndOffKeepsMemoryFlat}"

run_one() {
  local kind="$1" flags build
  case "$kind" in
    thread) flags="-fsanitize=thread" ;;
    address) flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined" ;;
    *) die "unknown sanitizer '$kind' (thread or address)" ;;
  esac
  build="$ROOT/build-tsan"
  [ "$kind" = address ] && build="$ROOT/build-asan"
  mkdir -p "$LOGS"
  echo "== $kind: configuring and building in $build"
  if ! cmake -S "$ROOT" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS="$flags -fno-omit-frame-pointer" \
    -DCMAKE_CXX_FLAGS="$flags -fno-omit-frame-pointer" \
    -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
    >"$LOGS/$kind-configure.log" 2>&1; then
    tail -n 20 "$LOGS/$kind-configure.log" >&2
    die "configure failed ($LOGS/$kind-configure.log)"
  fi
  if ! cmake --build "$build" -j "$(nproc)" --target "${TARGETS[@]}" >"$LOGS/$kind-build.log" 2>&1; then
    grep -E "error" "$LOGS/$kind-build.log" | head -n 20 >&2
    die "build failed ($LOGS/$kind-build.log)"
  fi
  local supp="$ROOT/scripts/sanitize"
  local status=0 t
  for t in "${TARGETS[@]}"; do
    echo "== $kind: $t"
    # (Through OSMesa, with no X server, as the test command runs them.)
    # (VTK's own SMP threads are TBB's, which the sanitizer cannot see synchronize: VTK runs
    # its loops on this thread instead. The project's worker threads are std::async's.)
    env -u DISPLAY VTK_SMP_BACKEND_IN_USE=Sequential \
      TSAN_OPTIONS="halt_on_error=0 exitcode=66 second_deadlock_stack=1 suppressions=$supp/tsan.supp" \
      ASAN_OPTIONS="detect_leaks=1 exitcode=66" \
      LSAN_OPTIONS="suppressions=$supp/lsan.supp print_suppressions=0" \
      UBSAN_OPTIONS="print_stacktrace=1 halt_on_error=1 suppressions=$supp/ubsan.supp" \
      "$build/Testing/$t" --gtest_filter="$FILTER" --gtest_brief=1 \
      >"$LOGS/$kind-$t.log" 2>&1 || status=$?
    grep -E "^\[  (PASSED|FAILED) |^SUMMARY: |WARNING: ThreadSanitizer|ERROR: AddressSanitizer|runtime error" \
      "$LOGS/$kind-$t.log" | sort | uniq -c || true
    if [ "$status" -ne 0 ]; then
      echo "$kind: $t failed (exit $status; full log: $LOGS/$kind-$t.log)" >&2
      return 1
    fi
  done
  echo "== $kind: clean"
}

kinds=("$@")
[ ${#kinds[@]} -eq 0 ] && kinds=(thread address)
result=0
for kind in "${kinds[@]}"; do
  run_one "$kind" || result=1
done
exit "$result"

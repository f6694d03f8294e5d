#!/usr/bin/env bash
# The tests: set up, build, then run every CTest test (GL tests under a virtual display).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$BUILD"
with_display ctest --output-on-failure "$@"

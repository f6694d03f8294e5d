#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The full speed-against-error benchmark: every scene, path, light sweep and technique at equal
# shadow-map texels. Writes build/bench/results.csv (+ .views.csv) and build/bench/plot.png.
# Takes about an hour on 2 cores with software Mesa. Extra arguments go to csm-bench.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mkdir -p "$BUILD/bench"
run_gl "$BUILD/Examples/csm-bench" --out "$BUILD/bench/results.csv" \
  --plot "$BUILD/bench/plot.png" "$@"

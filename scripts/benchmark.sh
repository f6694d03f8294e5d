#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Benchmark of the per-frame shadow math (Google Benchmark, medians of 5 repetitions).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
"$BUILD/Testing/csmMathBenchmark" "$@"

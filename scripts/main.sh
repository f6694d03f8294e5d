#!/usr/bin/env bash
# The main job: set up, build, then print the analytic speed-against-error table.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
"$BUILD/Examples/csm-analyze" --table

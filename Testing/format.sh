#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The format test: every C and C++ source of the project in the style of .clang-format (VTK's).
# Prints what clang-format would change and fails when it would change anything.
#   format.sh <clang-format> <project root>
set -euo pipefail
format="$1"
cd "$2"
mapfile -t sources < <(find Module Examples Support Testing ParaView -type f \
  \( -name '*.h' -o -name '*.cxx' -o -name '*.c' \) | sort)
echo "checking ${#sources[@]} sources with $("$format" --version)"
"$format" --dry-run --Werror "${sources[@]}"
echo "all ${#sources[@]} sources formatted"

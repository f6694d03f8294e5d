#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# expect-one-line-failure.sh <words> <program> [arguments]: the program must print exactly one
# line that holds <words> and exit with a non-zero status that is not a signal's.
words="$1"
shift
out=$("$@" 2>&1)
status=$?
printf '%s\n' "$out"
echo "exit status: $status"
if [ "$status" -eq 0 ] || [ "$status" -ge 126 ]; then
  echo "FAIL: expected a failure status (1-125), got $status"
  exit 1
fi
if [ "$(printf '%s\n' "$out" | wc -l)" -ne 1 ]; then
  echo "FAIL: expected one line"
  exit 1
fi
if ! printf '%s\n' "$out" | grep -qF -- "$words"; then
  echo "FAIL: the message does not say '$words'"
  exit 1
fi
echo "ok"

#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# expect-refusal.sh <program>: the program must exit with status 2 (not a signal, not 0) and
# print the OSMesa window's link-order message.
out=$("$1" 2>&1)
status=$?
printf '%s\n' "$out"
echo "exit status: $status"
if [ "$status" -ne 2 ]; then
  echo "FAIL: expected exit status 2 (a refusal), got $status"
  exit 1
fi
for words in "OSMesa render window refused" "glXGetProcAddressARB binds to" \
  "ahead of libGLX, libGL and libOpenGL"; do
  if ! printf '%s\n' "$out" | grep -qF "$words"; then
    echo "FAIL: the message does not say '$words'"
    exit 1
  fi
done
echo "ok: refused with the link-order message"

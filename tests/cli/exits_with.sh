#!/bin/sh
# usage: exits_with.sh <expected exit code> <command> [arguments…]
# Passes only when the command exits with exactly that code: WILL_FAIL would also pass on a crash,
# an abort or the wrong code, and scripts rely on the codes of controller/cli/exit_codes.hpp.
expected=$1
shift
"$@"
rc=$?
if [ "$rc" -ne "$expected" ]; then
  echo "FAIL: exit $rc, expected $expected: $*" >&2
  exit 1
fi

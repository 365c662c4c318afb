#!/bin/sh
# usage: exits_with.sh <expected exit code> [--says <text>] <command> [arguments…]
# Passes only when the command exits with exactly that code: WILL_FAIL would also pass on a crash,
# an abort or the wrong code, and scripts rely on the codes of controller/exit_codes/exit_codes.hpp.
# With --says, its output (stdout and stderr) must also contain <text>: the reason, not only the code.
expected=$1
shift
says=""
if [ "$1" = "--says" ]; then
  says=$2
  shift 2
fi
output=$("$@" 2>&1)
rc=$?
printf '%s\n' "$output"
if [ "$rc" -ne "$expected" ]; then
  echo "FAIL: exit $rc, expected $expected: $*" >&2
  exit 1
fi
if [ -n "$says" ] && ! printf '%s\n' "$output" | grep -qF -- "$says"; then
  echo "FAIL: the output does not say \"$says\": $*" >&2
  exit 1
fi

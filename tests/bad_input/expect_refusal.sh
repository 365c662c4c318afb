#!/bin/sh
# usage: expect_refusal.sh <exit status> <shown file> <line:column> <fragment> <command…>
# Runs the command (the real cellctl) and passes only when it exits with exactly that status and
# prints a line "<shown file>:<line:column>: …" that contains the fragment.
expected=$1 file=$2 position=$3 fragment=$4
shift 4
command="$*"
output=$("$@" 2>&1)
rc=$?
fail() {
  printf 'FAIL: %s\n  command: %s\n  output:\n%s\n' "$1" "$command" "$output" >&2
  exit 1
}
[ "$rc" -eq "$expected" ] || fail "exit $rc, expected $expected"
line=$(printf '%s\n' "$output" | grep -F -- "$file:$position: " | head -n 1)
[ -n "$line" ] || fail "no line starts with '$file:$position: '"
case $line in
  *"$fragment"*) ;;
  *) fail "'$fragment' is not in: $line" ;;
esac
